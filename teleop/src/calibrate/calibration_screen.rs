//! Drawing a [`CalibrationView`] full-screen with ratatui, in the trial console's look
//! ([`crate::console::screen`]): the pose and its instruction on top, the seven poses and the
//! session beside each other, the state with the capture-quality meter and the fit's
//! progress, the fit's table, the messages, the key bar.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Gauge, Paragraph};

use crate::calibrate::calibration_view::{CalState, CalibrationView};
use crate::tui::panels::{draw_heading, draw_messages, draw_rows, level_style};

/// The keys, as the key bar shows them.
pub const CALIBRATION_KEY_HELP: &str =
    "r retry the pose · space/Enter accept a poor capture · q quit";

fn banner_style(state: CalState) -> Style {
    let color = match state {
        CalState::WaitingGlove | CalState::Review => Color::Yellow,
        CalState::Settling => Color::Cyan,
        CalState::Capturing => Color::LightGreen,
        CalState::Fitting => Color::White,
        CalState::Complete => Color::Green,
        CalState::Failed => Color::Red,
    };
    Style::new().fg(color).add_modifier(Modifier::BOLD)
}

/// Draws the console.
pub fn draw_calibration(frame: &mut Frame<'_>, view: &CalibrationView) {
    let middle_rows = u16::try_from(view.poses.len().max(view.setup.len())).unwrap_or(8) + 2;
    let results_rows = u16::try_from(view.results.len()).unwrap_or(10).clamp(1, 12) + 2;
    let [top, middle, state, results, messages, keys] = Layout::vertical([
        Constraint::Length(4),
        Constraint::Length(middle_rows),
        Constraint::Length(7),
        Constraint::Length(results_rows),
        Constraint::Min(3),
        Constraint::Length(1),
    ])
    .areas(frame.area());

    draw_heading(
        frame,
        top,
        "POMDAR calibration console",
        &view.title,
        &view.instruction,
    );

    let [poses_area, setup_area] =
        Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)]).areas(middle);
    let poses = view
        .poses
        .iter()
        .map(|(name, status, level)| (name.as_str(), status.as_str(), Some(*level)));
    draw_rows(frame, poses_area, "Poses", 14, poses);
    let setup = view
        .setup
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str(), None));
    draw_rows(frame, setup_area, "Session", 10, setup);

    let block = Block::bordered().title(" State ");
    let inner = block.inner(state);
    frame.render_widget(block, state);
    let [banner_area, detail_area, meter_area, progress_area] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(2),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(inner);
    frame.render_widget(
        Paragraph::new(Span::styled(view.banner.clone(), banner_style(view.state))),
        banner_area,
    );
    frame.render_widget(
        Paragraph::new(
            view.detail
                .iter()
                .map(|d| Line::from(d.clone()))
                .collect::<Vec<_>>(),
        ),
        detail_area,
    );
    if let Some((fill, label, level)) = &view.meter {
        frame.render_widget(
            Gauge::default()
                .gauge_style(level_style(*level))
                .ratio(fill.clamp(0.0, 1.0))
                .label(format!("quality: {label}")),
            meter_area,
        );
    }
    if let Some((done, label)) = &view.progress {
        frame.render_widget(
            Gauge::default()
                .gauge_style(Style::new().fg(Color::Cyan))
                .ratio(done.clamp(0.0, 1.0))
                .label(format!("fit: {label}")),
            progress_area,
        );
    }

    let result_lines: Vec<Line> = view.results.iter().map(|r| Line::from(r.clone())).collect();
    frame.render_widget(
        Paragraph::new(result_lines).block(Block::bordered().title(" Errors before / after ")),
        results,
    );

    draw_messages(frame, messages, &view.messages);
    frame.render_widget(
        Paragraph::new(Line::from(Span::styled(
            CALIBRATION_KEY_HELP,
            Style::new().fg(Color::Gray),
        ))),
        keys,
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::panels::Level;
    use ratatui::Terminal;
    use ratatui::backend::TestBackend;

    #[test]
    fn the_screen_shows_the_pose_the_meter_and_the_keys() {
        let view = CalibrationView {
            state: CalState::Review,
            title: "[3/7] pinch_ring".into(),
            instruction: "Touch the tip of your thumb to the tip of your ring finger.".into(),
            setup: vec![("user".into(), "alice".into())],
            poses: vec![("pinch_ring".into(), "now (so far: bad)".into(), Level::Warn)],
            banner: "CAPTURE REVIEW".into(),
            detail: vec!["bad capture: r captures the pose again".into()],
            meter: Some((0.0, "pinch_ring capture 1: BAD".into(), Level::Bad)),
            progress: None,
            results: Vec::new(),
            messages: vec!["[3/7] pinch_ring: ...".into()],
        };
        let mut terminal = Terminal::new(TestBackend::new(100, 40)).unwrap();
        terminal.draw(|f| draw_calibration(f, &view)).unwrap();
        let text: String = terminal
            .backend()
            .buffer()
            .content()
            .iter()
            .map(|c| c.symbol())
            .collect();
        for wanted in [
            "POMDAR calibration console",
            "[3/7] pinch_ring",
            "CAPTURE REVIEW",
            "quality: pinch_ring capture 1: BAD",
            "r retry the pose",
        ] {
            assert!(text.contains(wanted), "{wanted:?} not on the screen");
        }
    }
}
