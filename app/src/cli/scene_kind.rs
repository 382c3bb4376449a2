//! The scene choice of `regatta render` and `regatta run` (its own module: the desktop window
//! reads it without reaching into the `render` command).

/// The scenes `regatta render` and `regatta run` draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum SceneKind {
    #[default]
    Race,
    Pool,
}
