//! Real input devices through libinput (`stratad serve --input libinput`): touchscreens,
//! mice and keyboards, read on a thread of their own and turned into the same actions
//! `ctl input` takes, on one output, so that every source is routed alike. Keys go through
//! xkbcommon's keyboard map: a key that types text becomes text, a named key (Return, the
//! arrows, F1…) its name.

use std::fs::{File, OpenOptions};
use std::os::fd::{AsRawFd, OwnedFd};
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Path, PathBuf};
use std::time::Duration;

use input::event::keyboard::{KeyState, KeyboardEvent, KeyboardEventTrait};
use input::event::pointer::{ButtonState, PointerEvent};
use input::event::touch::{TouchEvent, TouchEventPosition, TouchEventSlot};
use input::event::{DeviceEvent, Event, EventTrait};
use input::{Libinput, LibinputInterface};
use strata_protocol::input::{Action, Device};
use tracing::{debug, info, warn};
use xkbcommon::xkb;

/// Where input comes from besides `ctl input` and the output windows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Source {
    /// No device is read.
    #[default]
    None,
    /// evdev devices through libinput: the seat's (udev), or those `--input-device` names.
    Libinput,
}

/// Which device input routing reads the texels under a point on (`--input-pick`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum PickDevice {
    /// A device of its own that imports every shared frame too, so that a pick never waits
    /// behind the compositor's work.
    #[default]
    Own,
    /// The compositor's device: no extra device, but a pick waits for a composite in flight.
    Compositor,
}

/// The `--input*` options of `stratad serve`.
#[derive(Debug, Clone, clap::Args)]
pub struct InputArgs {
    /// Read real input devices: `libinput` reads the seat's evdev devices (off by default).
    #[arg(long, value_enum, default_value_t = Source::None)]
    pub input: Source,
    /// The udev seat whose devices libinput reads.
    #[arg(long, default_value = "seat0")]
    pub input_seat: String,
    /// Read these evdev devices (`/dev/input/eventN`) instead of the seat's; repeatable.
    #[arg(long = "input-device", value_name = "PATH")]
    pub input_devices: Vec<PathBuf>,
    /// The output the devices act on (default: the first).
    #[arg(long, value_name = "NAME", default_value = "")]
    pub input_output: String,
    /// The keyboard layout keys are read with (an XKB layout name).
    #[arg(long, default_value = "us")]
    pub input_layout: String,
    /// The device picks read texels on: `own` (imports every shared frame) or `compositor`.
    #[arg(long, value_enum, default_value_t = PickDevice::Own)]
    pub input_pick: PickDevice,
    /// Real-time priority (SCHED_FIFO, 1–99) of input routing and its pick device's threads,
    /// where the daemon may (CAP_SYS_NICE, or LimitRTPRIO=); 0: the high class's nice value.
    #[arg(long, value_name = "PRIO", default_value_t = 10, value_parser = clap::value_parser!(u8).range(0..=99))]
    pub input_realtime: u8,
}

impl Default for InputArgs {
    fn default() -> Self {
        InputArgs {
            input: Source::None,
            input_seat: "seat0".into(),
            input_devices: Vec::new(),
            input_output: String::new(),
            input_layout: "us".into(),
            input_pick: PickDevice::Own,
            input_realtime: 10,
        }
    }
}

/// Why the devices cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum LibinputError {
    /// A device named with `--input-device` did not open.
    #[error("input device {path}: {reason}")]
    Device {
        /// The path.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// The seat could not be read.
    #[error("libinput could not read seat {0:?} (is udev running, and may this user read /dev/input?)")]
    Seat(String),
    /// The keyboard layout did not compile.
    #[error("keyboard layout {0:?} is not an XKB layout this machine has (package xkb-data)")]
    Layout(String),
    /// The output they act on does not exist.
    #[error("--input-output: {0}")]
    Output(String),
    /// The reading thread did not start.
    #[error("the input device thread: {0}")]
    Thread(String),
}

/// Opens devices for libinput as the daemon's own user.
struct Opener;

impl LibinputInterface for Opener {
    fn open_restricted(&mut self, path: &Path, flags: i32) -> Result<OwnedFd, i32> {
        let access = flags & libc::O_ACCMODE;
        OpenOptions::new()
            .custom_flags(flags & !libc::O_ACCMODE)
            .read(access == libc::O_RDONLY || access == libc::O_RDWR)
            .write(access == libc::O_WRONLY || access == libc::O_RDWR)
            .open(path)
            .map(OwnedFd::from)
            .map_err(|e| -e.raw_os_error().unwrap_or(libc::EIO))
    }

    fn close_restricted(&mut self, fd: OwnedFd) {
        drop(File::from(fd));
    }
}

/// The X11 button number of an evdev button code (`BTN_LEFT`…), as the output windows number
/// theirs.
fn button(code: u32) -> u32 {
    match code {
        0x110 => 1,
        0x111 => 3,
        0x112 => 2,
        0x113 => 8,
        0x114 => 9,
        other => other.saturating_sub(0x110) + 1,
    }
}

/// Devices' events as actions: the pointer's position on the output, its held buttons, and
/// the keyboard's state (modifiers included).
pub struct Translator {
    at: (f64, f64),
    held: Vec<u32>,
    keys: xkb::State,
}

impl Translator {
    /// A translator whose keyboard map is XKB layout `layout`.
    pub fn new(layout: &str) -> Result<Translator, LibinputError> {
        let ctx = xkb::Context::new(xkb::CONTEXT_NO_FLAGS);
        let keymap = xkb::Keymap::new_from_names(&ctx, "", "", layout, "", None, xkb::COMPILE_NO_FLAGS)
            .ok_or_else(|| LibinputError::Layout(layout.to_string()))?;
        Ok(Translator { at: (0.0, 0.0), held: Vec::new(), keys: xkb::State::new(&keymap) })
    }

    /// Move events for every held button, from the pointer's position.
    fn moved(&self) -> Vec<Action> {
        let (x, y) = (self.at.0 as f32, self.at.1 as f32);
        self.held.iter().map(|&id| Action::Move { device: Device::Pointer, id, x, y }).collect()
    }

    /// The pointer moved by `d` (clamped to the output's `size`).
    pub fn motion(&mut self, d: (f64, f64), size: (u32, u32)) -> Vec<Action> {
        let max = (f64::from(size.0.max(1)) - 1.0, f64::from(size.1.max(1)) - 1.0);
        self.at = ((self.at.0 + d.0).clamp(0.0, max.0), (self.at.1 + d.1).clamp(0.0, max.1));
        self.moved()
    }

    /// The pointer is at output point `p`.
    pub fn absolute(&mut self, p: (f64, f64)) -> Vec<Action> {
        self.at = p;
        self.moved()
    }

    /// Evdev button `code` went down or up.
    pub fn button(&mut self, code: u32, pressed: bool) -> Vec<Action> {
        let id = button(code);
        let (x, y) = (self.at.0 as f32, self.at.1 as f32);
        match pressed {
            true if !self.held.contains(&id) => {
                self.held.push(id);
                vec![Action::Press { device: Device::Pointer, id, x, y }]
            }
            false if self.held.contains(&id) => {
                self.held.retain(|&h| h != id);
                vec![Action::Release { device: Device::Pointer, id }]
            }
            _ => Vec::new(),
        }
    }

    /// Evdev key `code` went down or up: on the way down, the text it types, else its name
    /// where `ctl input key` knows it.
    pub fn key(&mut self, code: u32, pressed: bool) -> Vec<Action> {
        // XKB numbers keys as X does: the evdev code plus 8.
        let key = xkb::Keycode::new(code + 8);
        let text = self.keys.key_get_utf8(key);
        let sym = self.keys.key_get_one_sym(key);
        let name = xkb::keysym_get_name(sym);
        let direction = if pressed { xkb::KeyDirection::Down } else { xkb::KeyDirection::Up };
        self.keys.update_key(key, direction);
        // Modifiers only change what other keys type.
        if !pressed || sym.is_modifier_key() {
            return Vec::new();
        }
        if !text.is_empty() && !text.chars().any(char::is_control) {
            return vec![Action::Text { text }];
        }
        if strata_protocol::input::keysym(&name).is_ok() {
            return vec![Action::Key { name }];
        }
        debug!(code, name, "a key with neither text nor a known name");
        Vec::new()
    }
}

/// A touch point as an action: down, moved or up, at output point `p`.
fn touch(id: u32, phase: Option<(f64, f64)>, down: bool) -> Action {
    match (phase, down) {
        (Some((x, y)), true) => Action::Press { device: Device::Touch, id, x: x as f32, y: y as f32 },
        (Some((x, y)), false) => Action::Move { device: Device::Touch, id, x: x as f32, y: y as f32 },
        (None, _) => Action::Release { device: Device::Touch, id },
    }
}

/// One libinput event as actions, for an output of `size` pixels.
fn actions(t: &mut Translator, event: Event, size: (u32, u32)) -> Vec<Action> {
    match event {
        Event::Device(DeviceEvent::Added(d)) => {
            info!(device = %d.device().name(), "input device added");
            Vec::new()
        }
        Event::Device(DeviceEvent::Removed(d)) => {
            info!(device = %d.device().name(), "input device removed");
            Vec::new()
        }
        Event::Keyboard(KeyboardEvent::Key(k)) => t.key(k.key(), k.key_state() == KeyState::Pressed),
        Event::Pointer(PointerEvent::Motion(m)) => t.motion((m.dx(), m.dy()), size),
        Event::Pointer(PointerEvent::MotionAbsolute(m)) => {
            t.absolute((m.absolute_x_transformed(size.0), m.absolute_y_transformed(size.1)))
        }
        Event::Pointer(PointerEvent::Button(b)) => t.button(b.button(), b.button_state() == ButtonState::Pressed),
        Event::Touch(TouchEvent::Down(e)) => {
            vec![touch(e.seat_slot(), Some((e.x_transformed(size.0), e.y_transformed(size.1))), true)]
        }
        Event::Touch(TouchEvent::Motion(e)) => {
            vec![touch(e.seat_slot(), Some((e.x_transformed(size.0), e.y_transformed(size.1))), false)]
        }
        Event::Touch(TouchEvent::Up(e)) => vec![touch(e.seat_slot(), None, false)],
        Event::Touch(TouchEvent::Cancel(e)) => vec![touch(e.seat_slot(), None, false)],
        _ => Vec::new(),
    }
}

/// Opens the devices `args` names (or its seat's) and reads them on a thread of its own until
/// `send` refuses an action; `size` is the output's size in pixels. Returns once the devices
/// are open, or why they did not open.
pub fn start(
    args: &InputArgs,
    size: (u32, u32),
    send: impl Fn(Action) -> bool + Send + 'static,
) -> Result<(), LibinputError> {
    let args = args.clone();
    let (ready_tx, ready) = std::sync::mpsc::channel();
    std::thread::Builder::new()
        .name("libinput".into())
        .spawn(move || {
            strata_device::set_thread_class(strata_protocol::control::Priority::High);
            let opened = open(&args).and_then(|li| Ok((li, Translator::new(&args.input_layout)?)));
            let (mut li, mut t) = match opened {
                Ok(v) => {
                    let _ = ready_tx.send(Ok(()));
                    v
                }
                Err(e) => {
                    let _ = ready_tx.send(Err(e));
                    return;
                }
            };
            let fd = li.as_raw_fd();
            let mut first = true;
            loop {
                let mut poll = libc::pollfd { fd, events: libc::POLLIN, revents: 0 };
                // SAFETY: one pollfd, valid for the call.
                let n = unsafe { libc::poll(&mut poll, 1, 250) };
                if n < 0 && std::io::Error::last_os_error().kind() != std::io::ErrorKind::Interrupted {
                    warn!("input devices: poll failed: {}", std::io::Error::last_os_error());
                    return;
                }
                if let Err(e) = li.dispatch() {
                    warn!("input devices: {e}");
                    return;
                }
                let mut added = 0;
                for event in &mut li {
                    added += usize::from(matches!(event, Event::Device(DeviceEvent::Added(_))));
                    for action in actions(&mut t, event, size) {
                        if !send(action) {
                            return;
                        }
                    }
                }
                if std::mem::take(&mut first) && added == 0 {
                    warn!(seat = args.input_seat, "libinput found no input device; it reads those that appear later");
                }
            }
        })
        .map_err(|e| LibinputError::Thread(e.to_string()))?;
    ready.recv_timeout(Duration::from_secs(10)).map_err(|e| LibinputError::Thread(e.to_string()))?
}

/// A libinput context on `args`' devices, or on its seat.
fn open(args: &InputArgs) -> Result<Libinput, LibinputError> {
    if args.input_devices.is_empty() {
        let mut li = Libinput::new_with_udev(Opener);
        li.udev_assign_seat(&args.input_seat).map_err(|()| LibinputError::Seat(args.input_seat.clone()))?;
        info!(seat = args.input_seat, "reading the seat's input devices through libinput");
        return Ok(li);
    }
    let mut li = Libinput::new_from_path(Opener);
    for path in &args.input_devices {
        let device = |reason: String| LibinputError::Device { path: path.clone(), reason };
        // libinput logs why a device fails, not to the caller: open it first to say why.
        OpenOptions::new().read(true).open(path).map_err(|e| device(e.to_string()))?;
        let name = path.to_str().ok_or_else(|| device("the path is not UTF-8".into()))?;
        li.path_add_device(name).ok_or_else(|| device("libinput does not take it as an input device".into()))?;
    }
    info!(devices = args.input_devices.len(), "reading input devices through libinput");
    Ok(li)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(t: &mut Translator, code: u32) -> Vec<Action> {
        let mut a = t.key(code, true);
        a.extend(t.key(code, false));
        a
    }

    #[test]
    fn keys_type_text_with_their_modifiers_and_named_keys_by_name() {
        let Ok(mut t) = Translator::new("us") else {
            assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "no XKB data: install xkb-data");
            return;
        };
        // KEY_A is 30, KEY_LEFTSHIFT 42, KEY_ENTER 28, KEY_1 2, KEY_F1 59.
        assert_eq!(text(&mut t, 30), vec![Action::Text { text: "a".into() }]);
        assert!(t.key(42, true).is_empty());
        assert_eq!(text(&mut t, 30), vec![Action::Text { text: "A".into() }]);
        assert_eq!(text(&mut t, 2), vec![Action::Text { text: "!".into() }]);
        assert!(t.key(42, false).is_empty());
        assert_eq!(text(&mut t, 2), vec![Action::Text { text: "1".into() }]);
        assert_eq!(text(&mut t, 28), vec![Action::Key { name: "Return".into() }]);
        assert_eq!(text(&mut t, 59), vec![Action::Key { name: "F1".into() }]);
    }

    #[test]
    fn a_pointer_drags_within_the_output_and_touch_points_keep_their_slots() {
        let Ok(mut t) = Translator::new("us") else { return };
        assert!(t.motion((50.0, 20.0), (100, 80)).is_empty(), "no button held: no event");
        assert_eq!(t.button(0x110, true), vec![Action::Press { device: Device::Pointer, id: 1, x: 50.0, y: 20.0 }]);
        assert_eq!(t.button(0x110, true), Vec::new(), "a repeated press is not a second one");
        // Motion stops at the output's last pixel.
        assert_eq!(
            t.motion((500.0, -70.0), (100, 80)),
            vec![Action::Move { device: Device::Pointer, id: 1, x: 99.0, y: 0.0 }]
        );
        assert_eq!(
            t.motion((0.0, 500.0), (100, 80)),
            vec![Action::Move { device: Device::Pointer, id: 1, x: 99.0, y: 79.0 }]
        );
        assert_eq!(
            t.motion((0.0, -79.0), (100, 80)),
            vec![Action::Move { device: Device::Pointer, id: 1, x: 99.0, y: 0.0 }]
        );
        assert_eq!(t.button(0x111, true), vec![Action::Press { device: Device::Pointer, id: 3, x: 99.0, y: 0.0 }]);
        assert_eq!(t.button(0x110, false), vec![Action::Release { device: Device::Pointer, id: 1 }]);
        assert_eq!(t.absolute((10.0, 10.0)), vec![Action::Move { device: Device::Pointer, id: 3, x: 10.0, y: 10.0 }]);
        assert_eq!(touch(4, Some((1.0, 2.0)), true), Action::Press { device: Device::Touch, id: 4, x: 1.0, y: 2.0 });
        assert_eq!(touch(4, None, true), Action::Release { device: Device::Touch, id: 4 });
    }
}
