//! Drawing a [`ConsoleView`] full-screen with ratatui.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use super::keys::KEY_HELP;
use super::view::{ConsoleView, Level, Screen};

fn level_style(level: Level) -> Style {
    match level {
        Level::Ok => Style::new().fg(Color::Green),
        Level::Warn => Style::new().fg(Color::Yellow),
        Level::Bad => Style::new().fg(Color::Red).add_modifier(Modifier::BOLD),
    }
}

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

    let task = Paragraph::new(vec![
        Line::from(Span::styled(
            view.title.clone(),
            Style::new().add_modifier(Modifier::BOLD),
        )),
        Line::from(view.instruction.clone()),
    ])
    .wrap(Wrap { trim: true })
    .block(Block::bordered().title(" POMDAR trial console "));
    frame.render_widget(task, top);

    let [setup_area, health_area] =
        Layout::horizontal([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(middle);
    let setup: Vec<Line> = view
        .setup
        .iter()
        .map(|(k, v)| {
            Line::from(vec![
                Span::styled(format!("{k:<12}"), Style::new().fg(Color::Gray)),
                Span::raw(v.clone()),
            ])
        })
        .collect();
    frame.render_widget(
        Paragraph::new(setup).block(Block::bordered().title(" Session ")),
        setup_area,
    );
    let health: Vec<Line> = view
        .health
        .iter()
        .map(|(k, v, level)| {
            Line::from(vec![
                Span::styled(format!("{k:<11}"), Style::new().fg(Color::Gray)),
                Span::styled(v.clone(), level_style(*level)),
            ])
        })
        .collect();
    frame.render_widget(
        Paragraph::new(health).block(Block::bordered().title(" Health ")),
        health_area,
    );

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

    let shown = usize::from(messages.height.saturating_sub(2));
    let skip = view.messages.len().saturating_sub(shown);
    let message_lines: Vec<Line> = view
        .messages
        .iter()
        .skip(skip)
        .map(|m| Line::from(m.clone()))
        .collect();
    frame.render_widget(
        Paragraph::new(message_lines).block(Block::bordered().title(" Messages ")),
        messages,
    );

    let bar = match prompt {
        Some(text) => Line::from(Span::styled(
            format!("{text}█  (Enter confirms, Esc cancels)"),
            Style::new().fg(Color::Cyan),
        )),
        None => Line::from(Span::styled(KEY_HELP, Style::new().fg(Color::Gray))),
    };
    frame.render_widget(Paragraph::new(bar), keys);
}
