//! Input from the daemon, delivered to the application as its own window system's events: a
//! thread of the library reads the connection's input events and sends each, as the matching
//! X11 event (`ButtonPress`, `MotionNotify`, `KeyPress`, `FocusIn`, …), to the X window of the
//! surface it is for, through a display connection of its own. Programs without an X window
//! (or without an X server) get nothing, but the events are still read, so that the daemon never
//! finds the client deaf.

use std::collections::HashMap;
use std::ffi::{c_int, c_long, c_uint, c_ulong};
use std::sync::Mutex;
use std::time::Duration;

use strata_client::input::InputReader;
use strata_protocol::input::{char_keysym, Device, InputEvent, Phase};
use x11_dl::xlib;

/// The X window of each window surface, by the daemon's surface ID.
static WINDOWS: Mutex<Option<HashMap<u64, u64>>> = Mutex::new(None);

/// Remembers that surface `id` shows X window `window`.
pub(crate) fn remember(id: u64, window: u64) {
    let mut w = WINDOWS.lock().unwrap_or_else(|p| p.into_inner());
    w.get_or_insert_with(HashMap::new).insert(id, window);
}

fn window_of(id: u64) -> Option<u64> {
    WINDOWS.lock().unwrap_or_else(|p| p.into_inner()).as_ref()?.get(&id).copied()
}

/// Starts the thread that delivers `reader`'s events; it ends with the connection.
pub(crate) fn start(mut reader: InputReader) {
    let spawned = std::thread::Builder::new().name("strata-input".into()).spawn(move || {
        let mut x: Option<Option<X>> = None;
        loop {
            match reader.next(Duration::from_secs(1)) {
                Ok(Some(e)) => {
                    let Some(window) = window_of(e.surface()) else {
                        tracing::debug!("strata-egl: an input event for surface {} without an X window", e.surface());
                        continue;
                    };
                    if let Some(x) = x.get_or_insert_with(X::open) {
                        x.send(window, &e);
                    }
                }
                Ok(None) => {}
                Err(e) => {
                    tracing::debug!("strata-egl: input ends: {e}");
                    return;
                }
            }
        }
    });
    if let Err(e) = spawned {
        tracing::warn!("strata-egl: no input thread ({e}); input events will not be read");
    }
}

/// The input thread's own X display connection.
struct X {
    lib: xlib::Xlib,
    display: *mut xlib::Display,
    root: c_ulong,
    /// Buttons held, as the state of motion and release events.
    held: c_uint,
}

impl X {
    /// Connects to `$DISPLAY`; `None` (logged) without libX11 or an X server.
    fn open() -> Option<X> {
        let lib = xlib::Xlib::open().map_err(|e| tracing::debug!("strata-egl: input without libX11: {e}")).ok()?;
        // SAFETY: XOpenDisplay(NULL) reads $DISPLAY; a null result means no server.
        let display = unsafe { (lib.XOpenDisplay)(std::ptr::null()) };
        if display.is_null() {
            tracing::debug!("strata-egl: input without an X server");
            return None;
        }
        // SAFETY: a display just opened.
        let root = unsafe { (lib.XDefaultRootWindow)(display) };
        Some(X { lib, display, root, held: 0 })
    }

    /// Sends `e` to `window` as the X11 events it stands for.
    fn send(&mut self, window: u64, e: &InputEvent) {
        match e {
            InputEvent::Point { device, id, phase, x, y, .. } => {
                // A touch acts as the first button, as X servers emulate it for core clients.
                let button = match device {
                    Device::Pointer => (*id).clamp(1, 5),
                    Device::Touch => 1,
                };
                let mask = 1 << (7 + button);
                let (kind, event_mask, state) = match phase {
                    Phase::Down => (xlib::ButtonPress, xlib::ButtonPressMask, self.held),
                    Phase::Motion => (
                        xlib::MotionNotify,
                        xlib::PointerMotionMask | xlib::ButtonMotionMask | (xlib::Button1MotionMask << (button - 1)),
                        self.held,
                    ),
                    Phase::Up => (xlib::ButtonRelease, xlib::ButtonReleaseMask, self.held),
                };
                self.held = match phase {
                    Phase::Down => self.held | mask,
                    Phase::Up => self.held & !mask,
                    Phase::Motion => self.held,
                };
                let (x, y) = (x.floor() as c_int, y.floor() as c_int);
                let b = xlib::XButtonEvent {
                    type_: kind,
                    serial: 0,
                    send_event: xlib::True,
                    display: self.display,
                    window,
                    root: self.root,
                    subwindow: 0,
                    time: xlib::CurrentTime,
                    x,
                    y,
                    x_root: x,
                    y_root: y,
                    state,
                    button,
                    same_screen: xlib::True,
                };
                let mut ev = xlib::XEvent { button: b };
                if kind == xlib::MotionNotify {
                    // The same layout, with `is_hint` (0) where the button was.
                    ev.motion.is_hint = 0;
                }
                self.deliver(window, event_mask, &mut ev);
            }
            InputEvent::Key { keysym, pressed, .. } => self.key(window, *keysym, *pressed),
            InputEvent::Text { text, .. } => {
                for c in text.chars() {
                    if let Some(k) = char_keysym(c) {
                        self.key(window, k, true);
                        self.key(window, k, false);
                    }
                }
            }
            InputEvent::Focus { focused, .. } => {
                let f = xlib::XFocusChangeEvent {
                    type_: if *focused { xlib::FocusIn } else { xlib::FocusOut },
                    serial: 0,
                    send_event: xlib::True,
                    display: self.display,
                    window,
                    mode: xlib::NotifyNormal,
                    detail: xlib::NotifyNonlinear,
                };
                let mut ev = xlib::XEvent { focus_change: f };
                self.deliver(window, xlib::FocusChangeMask, &mut ev);
            }
        }
    }

    /// A key press or release of `keysym`, with Shift where the keyboard map needs it; a
    /// keysym the map lacks is left out.
    fn key(&mut self, window: u64, keysym: u32, pressed: bool) {
        // SAFETY: queries of the thread's own display's keyboard map.
        let (code, shifted) = unsafe {
            let code = (self.lib.XKeysymToKeycode)(self.display, c_ulong::from(keysym));
            let plain = (self.lib.XkbKeycodeToKeysym)(self.display, code, 0, 0);
            (code, code != 0 && plain != c_ulong::from(keysym))
        };
        if code == 0 {
            tracing::debug!("strata-egl: keysym {keysym:#x} has no key in the X server's map");
            return;
        }
        let k = xlib::XKeyEvent {
            type_: if pressed { xlib::KeyPress } else { xlib::KeyRelease },
            serial: 0,
            send_event: xlib::True,
            display: self.display,
            window,
            root: self.root,
            subwindow: 0,
            time: xlib::CurrentTime,
            x: 0,
            y: 0,
            x_root: 0,
            y_root: 0,
            state: if shifted { xlib::ShiftMask } else { 0 },
            keycode: c_uint::from(code),
            same_screen: xlib::True,
        };
        let mut ev = xlib::XEvent { key: k };
        self.deliver(window, if pressed { xlib::KeyPressMask } else { xlib::KeyReleaseMask }, &mut ev);
    }

    fn deliver(&self, window: u64, mask: c_long, ev: &mut xlib::XEvent) {
        // SAFETY: an event built in full for a window of this X server, sent on the thread's
        // own display connection.
        unsafe {
            (self.lib.XSendEvent)(self.display, window, xlib::False, mask, ev);
            (self.lib.XFlush)(self.display);
        }
    }
}

impl Drop for X {
    fn drop(&mut self) {
        // SAFETY: the display this thread opened, closed once.
        unsafe { (self.lib.XCloseDisplay)(self.display) };
    }
}
