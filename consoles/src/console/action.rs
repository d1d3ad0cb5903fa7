//! The operator's actions on the trial console: the same actions come from the keyboard, a
//! `--script` file or a line on stdin (the words and keys are teleop's `console::keys`).

/// One thing the operator asks of the console.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// Engage if disengaged, disengage (clutch out) if engaged.
    ToggleEngage,
    /// Engage: drive the hand and arm once glove input is fresh.
    Engage,
    /// Disengage (clutch out): the arm stops where it is, the hand holds.
    Disengage,
    /// Start the next trial (with the countdown) when idle; stop the running trial.
    StartStop,
    /// Start the next trial (with the countdown).
    Start,
    /// Stop the running trial: the task is finished.
    Stop,
    /// A progress mark: `None` is one unit (one notch or curve), `Some(v)` a value in the
    /// task's unit (degrees, millimetres, or a grasp level 0 / 0.5 / 1).
    Progress(Option<f64>),
    /// Take back one unit of progress (a mark given by mistake).
    Unmark,
    /// Ask for a progress value (the console prompts for it).
    PromptProgress,
    /// The object fell.
    Drop,
    /// Abort the running trial (it is logged and scored as aborted), or cancel the countdown.
    Abort,
    /// Redo: abort the running trial, or set the last finished one aside, and run it again.
    Redo,
    /// A note: for the running trial's log, else for the session manifest.
    Note(String),
    /// Ask for a note (the console prompts for it).
    PromptNote,
    /// Quit (a running trial is aborted and set aside; the session resumes later).
    Quit,
    /// Ctrl-C: quit at once (a running trial is aborted and set aside).
    Interrupt,
}
