//! The interpreter: walks the IR directly, generic over f32 and f64. The f64 instance is the accuracy reference.
