//! The pieces both consoles draw the same way (the trial console's [`crate::console::screen`] and the
//! calibration console's): the heading with the instruction, labelled rows, the message log,
//! the colours of a level.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

/// How a value on a console reads: the core crate's (`consoles::Level`).
pub use consoles::Level;

/// The colour of a level: green, yellow, bold red.
pub fn level_style(level: Level) -> Style {
    match level {
        Level::Ok => Style::new().fg(Color::Green),
        Level::Warn => Style::new().fg(Color::Yellow),
        Level::Bad => Style::new().fg(Color::Red).add_modifier(Modifier::BOLD),
    }
}

/// The top panel: `console` in the border, the title in bold, the instruction wrapped.
pub fn draw_heading(frame: &mut Frame<'_>, area: Rect, console: &str, title: &str, text: &str) {
    let heading = Paragraph::new(vec![
        Line::from(Span::styled(
            title.to_string(),
            Style::new().add_modifier(Modifier::BOLD),
        )),
        Line::from(text.to_string()),
    ])
    .wrap(Wrap { trim: true })
    .block(Block::bordered().title(format!(" {console} ")));
    frame.render_widget(heading, area);
}

/// A bordered panel of `label  value` rows, the label padded to `width` in grey, the value
/// in its level's colour (plain where there is none).
pub fn draw_rows<'a>(
    frame: &mut Frame<'_>,
    area: Rect,
    title: &str,
    width: usize,
    rows: impl Iterator<Item = (&'a str, &'a str, Option<Level>)>,
) {
    let lines: Vec<Line> = rows
        .map(|(label, value, level)| {
            Line::from(vec![
                Span::styled(format!("{label:<width$}"), Style::new().fg(Color::Gray)),
                Span::styled(value.to_string(), level.map_or(Style::new(), level_style)),
            ])
        })
        .collect();
    frame.render_widget(
        Paragraph::new(lines).block(Block::bordered().title(format!(" {title} "))),
        area,
    );
}

/// The message log: the latest messages that fit.
pub fn draw_messages(frame: &mut Frame<'_>, area: Rect, messages: &[String]) {
    let shown = usize::from(area.height.saturating_sub(2));
    let skip = messages.len().saturating_sub(shown);
    let lines: Vec<Line> = messages
        .iter()
        .skip(skip)
        .map(|m| Line::from(m.clone()))
        .collect();
    frame.render_widget(
        Paragraph::new(lines).block(Block::bordered().title(" Messages ")),
        area,
    );
}
