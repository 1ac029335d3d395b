//! An output window's own input: its pointer, touch and key events (winit) as the same actions
//! `ctl input` takes, in the output's pixels, so that both sources are routed alike.

use strata_protocol::input::{Action, Device};
use winit::event::{ElementState, MouseButton, TouchPhase, WindowEvent};
use winit::keyboard::{Key, NamedKey};

/// What a window's events need remembered: where the pointer is, and its held buttons.
#[derive(Debug, Default)]
pub struct PointerState {
    at: (f32, f32),
    held: Vec<u32>,
}

/// The X11 button number of a winit button.
fn button(b: MouseButton) -> u32 {
    match b {
        MouseButton::Left => 1,
        MouseButton::Middle => 2,
        MouseButton::Right => 3,
        MouseButton::Back => 8,
        MouseButton::Forward => 9,
        MouseButton::Other(n) => u32::from(n),
    }
}

/// The keysym name of a winit named key, for the keys `ctl input key` knows.
fn key_name(k: NamedKey) -> Option<&'static str> {
    Some(match k {
        NamedKey::Enter => "Return",
        NamedKey::Backspace => "BackSpace",
        NamedKey::Tab => "Tab",
        NamedKey::Escape => "Escape",
        NamedKey::Delete => "Delete",
        NamedKey::Home => "Home",
        NamedKey::End => "End",
        NamedKey::ArrowLeft => "Left",
        NamedKey::ArrowRight => "Right",
        NamedKey::ArrowUp => "Up",
        NamedKey::ArrowDown => "Down",
        NamedKey::PageUp => "Page_Up",
        NamedKey::PageDown => "Page_Down",
        NamedKey::Insert => "Insert",
        NamedKey::F1 => "F1",
        NamedKey::F2 => "F2",
        NamedKey::F3 => "F3",
        NamedKey::F4 => "F4",
        NamedKey::F5 => "F5",
        NamedKey::F6 => "F6",
        NamedKey::F7 => "F7",
        NamedKey::F8 => "F8",
        NamedKey::F9 => "F9",
        NamedKey::F10 => "F10",
        NamedKey::F11 => "F11",
        NamedKey::F12 => "F12",
        _ => return None,
    })
}

impl PointerState {
    /// The actions one window event stands for (none for events that are not input).
    pub fn actions(&mut self, event: &WindowEvent) -> Vec<Action> {
        match event {
            WindowEvent::CursorMoved { position, .. } => {
                self.at = (position.x as f32, position.y as f32);
                let (x, y) = self.at;
                self.held.iter().map(|&id| Action::Move { device: Device::Pointer, id, x, y }).collect()
            }
            WindowEvent::MouseInput { state, button: b, .. } => {
                let (id, (x, y)) = (button(*b), self.at);
                match state {
                    ElementState::Pressed if !self.held.contains(&id) => {
                        self.held.push(id);
                        vec![Action::Press { device: Device::Pointer, id, x, y }]
                    }
                    ElementState::Released if self.held.contains(&id) => {
                        self.held.retain(|&h| h != id);
                        vec![Action::Release { device: Device::Pointer, id }]
                    }
                    _ => Vec::new(),
                }
            }
            WindowEvent::Touch(t) => {
                let (x, y) = (t.location.x as f32, t.location.y as f32);
                // Touch IDs are the window system's; the low 32 bits tell points apart.
                let id = t.id as u32;
                vec![match t.phase {
                    TouchPhase::Started => Action::Press { device: Device::Touch, id, x, y },
                    TouchPhase::Moved => Action::Move { device: Device::Touch, id, x, y },
                    TouchPhase::Ended | TouchPhase::Cancelled => Action::Release { device: Device::Touch, id },
                }]
            }
            WindowEvent::KeyboardInput { event, is_synthetic: false, .. } if event.state == ElementState::Pressed => {
                if let Some(name) = match &event.logical_key {
                    Key::Named(k) => key_name(*k),
                    _ => None,
                } {
                    return vec![Action::Key { name: name.to_string() }];
                }
                match &event.text {
                    Some(text) if !text.chars().any(char::is_control) => vec![Action::Text { text: text.to_string() }],
                    _ => Vec::new(),
                }
            }
            _ => Vec::new(),
        }
    }
}
