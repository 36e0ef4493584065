//! The command line's one error type: a message for stderr and the exit status it ends with — 2 for usage errors
//! (the command line asks for something impossible: a bad size, range, shard, backend, parameter or scene name),
//! 1 for failures while doing what was asked (a file that cannot be read or written, a device or ffmpeg failing).

use std::fmt;
use std::process::ExitCode;

use fractal_render::error::{FrameError, RenderError};

use crate::output::OutputError;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    Usage,
    Failure,
}

#[derive(Debug)]
pub struct CliError {
    pub kind: ErrorKind,
    pub message: String,
}

impl CliError {
    pub fn usage(message: impl Into<String>) -> CliError {
        CliError { kind: ErrorKind::Usage, message: message.into() }
    }
    pub fn failure(message: impl Into<String>) -> CliError {
        CliError { kind: ErrorKind::Failure, message: message.into() }
    }
    pub fn exit_code(&self) -> ExitCode {
        match self.kind {
            ErrorKind::Usage => ExitCode::from(2),
            ErrorKind::Failure => ExitCode::from(1),
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl From<OutputError> for CliError {
    fn from(e: OutputError) -> CliError {
        CliError::failure(e.to_string())
    }
}

impl From<RenderError> for CliError {
    fn from(e: RenderError) -> CliError {
        match e {
            // These come from what the command line asked for; other frame errors come from the scene.
            RenderError::Frame(
                frame @ (FrameError::ImageSize { .. }
                | FrameError::UnknownParam(_)
                | FrameError::ParamOutOfRange { .. }
                | FrameError::Time(_)),
            ) => CliError::usage(frame.to_string()),
            other => CliError::failure(other.to_string()),
        }
    }
}
