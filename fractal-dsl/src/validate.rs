//! Validation: every value a scene names is checked against its allowed range, with a message naming the parameter.
