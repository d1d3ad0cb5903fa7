//! Drawing a [`ConsoleView`] full-screen with ratatui.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use super::keys::KEY_HELP;
use super::view::{ConsoleView, Screen};
use crate::tui::panels::{draw_heading, draw_messages, draw_rows};

fn banner_style(screen: Screen) -> Style {
    let color = match screen {
        Screen::WaitingEngage => Color::Yellow,
        Screen::Ready | Screen::Complete => Color::Green,
        Screen::Countdown => Color::Cyan,
        Screen::Running => Color::LightGreen,
        Screen::Finishing | Screen::Summary => Color::White,
    };
    Style::new().fg(color).add_modifier(Modifier::BOLD)
}

/// Draws the console; `prompt` is the line being typed (a progress value or a note), if any.
pub fn draw(frame: &mut Frame<'_>, view: &ConsoleView, prompt: Option<&str>) {
    let setup_rows = u16::try_from(view.setup.len().max(view.health.len())).unwrap_or(12) + 2;
    let [top, middle, state, results, messages, keys] = Layout::vertical([
        Constraint::Length(4),
        Constraint::Length(setup_rows),
        Constraint::Length(6),
        Constraint::Length(4),
        Constraint::Min(3),
        Constraint::Length(1),
    ])
    .areas(frame.area());

    draw_heading(
        frame,
        top,
        "POMDAR trial console",
        &view.title,
        &view.instruction,
    );

    let [setup_area, health_area] =
        Layout::horizontal([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(middle);
    let setup = view
        .setup
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str(), None));
    draw_rows(frame, setup_area, "Session", 12, setup);
    let health = view
        .health
        .iter()
        .map(|(k, v, level)| (k.as_str(), v.as_str(), Some(*level)));
    draw_rows(frame, health_area, "Health", 11, health);

    let mut lines = vec![Line::from(Span::styled(
        view.banner.clone(),
        banner_style(view.screen),
    ))];
    lines.extend(view.detail.iter().map(|d| Line::from(d.clone())));
    frame.render_widget(
        Paragraph::new(lines).block(Block::bordered().title(" State ")),
        state,
    );

    let result_lines: Vec<Line> = view.results.iter().map(|r| Line::from(r.clone())).collect();
    frame.render_widget(
        Paragraph::new(result_lines)
            .wrap(Wrap { trim: true })
            .block(Block::bordered().title(" Results ")),
        results,
    );

    draw_messages(frame, messages, &view.messages);

    let bar = match prompt {
        Some(text) => Line::from(Span::styled(
            format!("{text}█  (Enter confirms, Esc cancels)"),
            Style::new().fg(Color::Cyan),
        )),
        None => Line::from(Span::styled(KEY_HELP, Style::new().fg(Color::Gray))),
    };
    frame.render_widget(Paragraph::new(bar), keys);
}
