//! Debug output (`GL_KHR_debug`): the messages a context generates (GL errors, messages the
//! application inserts, debug groups), the volume control that filters them, the debug group
//! stack, and the message log.
//!
//! **Where messages go.** While the application has no debug callback, enabled messages enter
//! the context's log (at most [`MAX_LOGGED`]; later ones are dropped until it is read). The
//! callback lives in the client library, so while it has one (`strataDebugCallback`), enabled
//! messages wait in a second queue instead, which the library drains with
//! `strataDebugMessages`: after every call when `DEBUG_OUTPUT_SYNCHRONOUS` is enabled, as the
//! extension requires, and otherwise only at points where it waits for the daemon anyway (see
//! the client library's `debug` module). Nothing is generated while `DEBUG_OUTPUT` is disabled,
//! its initial state in a context created without the debug flag.
//!
//! **Volume control.** Each debug group holds the `glDebugMessageControlKHR` rules made while it
//! was on top, in order, starting from a copy of its parent's; a message is enabled unless its
//! severity is `LOW`, and then as the last rule that matches it says. A rule that matches a
//! superset of an older rule's messages replaces it, which keeps the list short.

use super::context::Context;
use std::collections::VecDeque;

use strata_protocol::commands::{DebugMessage, MAX_DEBUG_MESSAGE_LENGTH};
use strata_protocol::{Blob, Bytes, Slice};

use super::enums::*;
use super::error::{GlError, GlResult};
use super::GlesExecutor;

/// `GL_MAX_DEBUG_LOGGED_MESSAGES_KHR`.
pub const MAX_LOGGED: usize = 64;
/// `GL_MAX_DEBUG_GROUP_STACK_DEPTH_KHR` (the default group included).
pub const MAX_GROUP_DEPTH: usize = 64;
/// Messages kept for the client's callback between two drains; later ones are dropped.
const MAX_PENDING: usize = 4096;
/// Message ids one group's rules may list in all (a quota, like every per-client resource).
const MAX_RULE_IDS: usize = 1 << 16;

/// One `glDebugMessageControlKHR` call: which messages it addresses and what it set.
#[derive(Clone)]
struct Rule {
    /// `None` is `GL_DONT_CARE`.
    source: Option<u32>,
    ty: Option<u32>,
    severity: Option<u32>,
    /// Empty: every id.
    ids: Vec<u32>,
    enabled: bool,
}

impl Rule {
    fn matches(&self, m: &DebugMessage) -> bool {
        self.source.is_none_or(|s| s == m.source)
            && self.ty.is_none_or(|t| t == m.ty)
            && self.severity.is_none_or(|s| s == m.severity)
            && (self.ids.is_empty() || self.ids.contains(&m.id))
    }

    /// Whether every message `older` matches is matched by `self` too.
    fn covers(&self, older: &Rule) -> bool {
        let field = |new: Option<u32>, old: Option<u32>| new.is_none() || new == old;
        field(self.source, older.source)
            && field(self.ty, older.ty)
            && field(self.severity, older.severity)
            && (self.ids.is_empty() || (!older.ids.is_empty() && older.ids.iter().all(|i| self.ids.contains(i))))
    }
}

/// One entry of the debug group stack.
#[derive(Clone)]
struct Group {
    source: u32,
    id: u32,
    text: Vec<u8>,
    rules: Vec<Rule>,
}

/// A context's debug output state.
pub struct DebugState {
    /// `GL_DEBUG_OUTPUT_KHR`.
    pub output: bool,
    /// `GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR`.
    pub synchronous: bool,
    /// Whether the application has a callback (messages go to `pending`, not `log`).
    callback: bool,
    log: VecDeque<DebugMessage>,
    pending: VecDeque<DebugMessage>,
    /// The group stack; the default group is at the bottom and is never popped.
    groups: Vec<Group>,
}

impl Default for DebugState {
    fn default() -> Self {
        DebugState {
            output: false,
            synchronous: false,
            callback: false,
            log: VecDeque::new(),
            pending: VecDeque::new(),
            groups: vec![Group { source: 0, id: 0, text: Vec::new(), rules: Vec::new() }],
        }
    }
}

/// Whether `s` is a message source (`GL_DEBUG_SOURCE_*_KHR`).
fn is_source(s: u32) -> bool {
    (DEBUG_SOURCE_API..=DEBUG_SOURCE_OTHER).contains(&s)
}

/// Whether `t` is a message type an application may insert.
fn is_insert_type(t: u32) -> bool {
    (DEBUG_TYPE_ERROR..=DEBUG_TYPE_OTHER).contains(&t) || t == DEBUG_TYPE_MARKER
}

/// Whether `s` is a severity.
fn is_severity(s: u32) -> bool {
    matches!(s, DEBUG_SEVERITY_HIGH | DEBUG_SEVERITY_MEDIUM | DEBUG_SEVERITY_LOW | DEBUG_SEVERITY_NOTIFICATION)
}

/// `None` for `GL_DONT_CARE`, else `v` if `valid`, else `GL_INVALID_ENUM`.
fn dont_care_or(v: u32, valid: bool) -> GlResult<Option<u32>> {
    match v {
        DONT_CARE => Ok(None),
        _ if valid => Ok(Some(v)),
        _ => Err(GlError::InvalidEnum),
    }
}

/// The text of an inserted message or group: `length` bytes, or with a negative `length` the
/// NUL-terminated text the client sent; `GL_INVALID_VALUE` if it is not shorter than the limit.
pub fn message_text(length: i32, text: &Blob<'_>, max: i32) -> GlResult<Vec<u8>> {
    let len = if length < 0 { text.len() } else { length as usize };
    if len >= max as usize || text.len() < len {
        return Err(GlError::InvalidValue);
    }
    Ok(text.as_bytes()[..len].to_vec())
}

impl DebugState {
    fn enabled(&self, m: &DebugMessage) -> bool {
        let rules = self.groups.last().map_or(&[][..], |g| &g.rules[..]);
        rules.iter().rev().find(|r| r.matches(m)).map_or(m.severity != DEBUG_SEVERITY_LOW, |r| r.enabled)
    }

    /// Generates a message: it reaches the log or the callback queue if output is enabled and
    /// the active group's volume control lets it through.
    pub fn emit(&mut self, source: u32, ty: u32, id: u32, severity: u32, text: Vec<u8>) {
        if !self.output {
            return;
        }
        let m = DebugMessage { source, ty, id, severity, text: Bytes(text) };
        if !self.enabled(&m) {
            return;
        }
        let (queue, cap) = if self.callback { (&mut self.pending, MAX_PENDING) } else { (&mut self.log, MAX_LOGGED) };
        if queue.len() < cap {
            queue.push_back(m);
        }
    }

    /// The message a GL error generates: source API, type ERROR, severity HIGH, the error's
    /// enum as its id, and a text naming the call.
    pub fn error(&mut self, call: &str, e: GlError) {
        if self.output {
            self.emit(
                DEBUG_SOURCE_API,
                DEBUG_TYPE_ERROR,
                e.as_gl(),
                DEBUG_SEVERITY_HIGH,
                format!("{e} in {call}").into(),
            );
        }
    }

    /// `GL_DEBUG_LOGGED_MESSAGES_KHR`.
    pub fn logged(&self) -> usize {
        self.log.len()
    }

    /// `GL_DEBUG_NEXT_LOGGED_MESSAGE_LENGTH_KHR`: the oldest message's length with its NUL.
    pub fn next_length(&self) -> usize {
        self.log.front().map_or(0, |m| m.text.0.len() + 1)
    }

    /// `GL_DEBUG_GROUP_STACK_DEPTH_KHR`.
    pub fn depth(&self) -> usize {
        self.groups.len()
    }

    fn control(&mut self, rule: Rule) -> GlResult {
        let group = self.groups.last_mut().ok_or(GlError::InvalidOperation)?;
        group.rules.retain(|old| !rule.covers(old));
        let ids: usize = group.rules.iter().map(|r| r.ids.len()).sum();
        if ids + rule.ids.len() > MAX_RULE_IDS {
            return Err(GlError::OutOfMemory);
        }
        group.rules.push(rule);
        Ok(())
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glDebugMessageControlKHR(
        &mut self,
        ctx: &mut Context,
        source: u32,
        ty: u32,
        severity: u32,
        count: i32,
        ids: Slice<'_, u32>,
        enabled: bool,
    ) -> GlResult {
        if count < 0 {
            return Err(GlError::InvalidValue);
        }
        let source = dont_care_or(source, is_source(source))?;
        let ty = dont_care_or(ty, is_insert_type(ty) || matches!(ty, DEBUG_TYPE_PUSH_GROUP | DEBUG_TYPE_POP_GROUP))?;
        let severity = dont_care_or(severity, is_severity(severity))?;
        if count > 0 && (source.is_none() || ty.is_none() || severity.is_some()) {
            return Err(GlError::InvalidOperation);
        }
        let ids: Vec<u32> = ids.iter().take(count as usize).collect();
        if count > 0 && ids.is_empty() {
            // Ids that were not sent (a null array) select nothing.
            return Ok(());
        }
        ctx.debug.control(Rule { source, ty, severity, ids, enabled })
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glDebugMessageInsertKHR(
        &mut self,
        ctx: &mut Context,
        source: u32,
        ty: u32,
        id: u32,
        severity: u32,
        length: i32,
        text: Blob<'_>,
    ) -> GlResult {
        if !matches!(source, DEBUG_SOURCE_APPLICATION | DEBUG_SOURCE_THIRD_PARTY)
            || !is_insert_type(ty)
            || !is_severity(severity)
        {
            return Err(GlError::InvalidEnum);
        }
        let text = message_text(length, &text, MAX_DEBUG_MESSAGE_LENGTH)?;
        ctx.debug.emit(source, ty, id, severity, text);
        Ok(())
    }

    pub(super) fn glPushDebugGroupKHR(
        &mut self,
        ctx: &mut Context,
        source: u32,
        id: u32,
        length: i32,
        text: Blob<'_>,
    ) -> GlResult {
        if !matches!(source, DEBUG_SOURCE_APPLICATION | DEBUG_SOURCE_THIRD_PARTY) {
            return Err(GlError::InvalidEnum);
        }
        let text = message_text(length, &text, MAX_DEBUG_MESSAGE_LENGTH)?;
        let debug = &mut ctx.debug;
        if debug.groups.len() >= MAX_GROUP_DEPTH {
            return Err(GlError::StackOverflow);
        }
        debug.emit(source, DEBUG_TYPE_PUSH_GROUP, id, DEBUG_SEVERITY_NOTIFICATION, text.clone());
        let rules = debug.groups.last().map(|g| g.rules.clone()).unwrap_or_default();
        debug.groups.push(Group { source, id, text, rules });
        Ok(())
    }

    pub(super) fn glPopDebugGroupKHR(&mut self, ctx: &mut Context) -> GlResult {
        let debug = &mut ctx.debug;
        if debug.groups.len() <= 1 {
            return Err(GlError::StackUnderflow);
        }
        let Some(g) = debug.groups.pop() else { return Err(GlError::StackUnderflow) };
        // The message is filtered by the parent's volume control, which is active again.
        debug.emit(g.source, DEBUG_TYPE_POP_GROUP, g.id, DEBUG_SEVERITY_NOTIFICATION, g.text);
        Ok(())
    }

    pub(super) fn strataDebugCallback(&mut self, ctx: &mut Context, installed: bool) -> GlResult {
        let debug = &mut ctx.debug;
        debug.callback = installed;
        if !installed {
            // Messages not yet delivered are lost with the callback, as a driver's would be.
            debug.pending.clear();
        }
        Ok(())
    }

    pub(super) fn strataDebugMessages(&mut self, ctx: &mut Context) -> Vec<DebugMessage> {
        ctx.debug.pending.drain(..).collect()
    }

    pub(super) fn glGetDebugMessageLogKHR(
        &mut self,
        ctx: &mut Context,
        count: u32,
        buf_size: i32,
        log: bool,
    ) -> Vec<DebugMessage> {
        if log && buf_size < 0 {
            ctx.record(GlError::InvalidValue);
            return Vec::new();
        }
        let debug = &mut ctx.debug;
        let mut room = if log { buf_size as usize } else { usize::MAX };
        let mut out = Vec::new();
        while out.len() < count as usize {
            let Some(m) = debug.log.front() else { break };
            let need = m.text.0.len() + 1;
            if need > room {
                break;
            }
            room -= need;
            out.extend(debug.log.pop_front());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn marker(debug: &mut DebugState, id: u32) {
        debug.emit(DEBUG_SOURCE_APPLICATION, DEBUG_TYPE_MARKER, id, DEBUG_SEVERITY_NOTIFICATION, b"m".to_vec());
    }

    fn rule(source: Option<u32>, ty: Option<u32>, severity: Option<u32>, ids: &[u32], enabled: bool) -> Rule {
        Rule { source, ty, severity, ids: ids.to_vec(), enabled }
    }

    #[test]
    fn nothing_is_generated_while_output_is_disabled_and_low_severity_starts_disabled() {
        let mut d = DebugState::default();
        marker(&mut d, 1);
        assert_eq!(d.logged(), 0);
        d.output = true;
        marker(&mut d, 1);
        d.emit(DEBUG_SOURCE_APPLICATION, DEBUG_TYPE_OTHER, 2, DEBUG_SEVERITY_LOW, b"low".to_vec());
        assert_eq!(d.logged(), 1);
        assert_eq!(d.next_length(), 2);
    }

    #[test]
    fn the_last_matching_rule_decides_and_covered_rules_are_dropped() {
        let mut d = DebugState { output: true, ..DebugState::default() };
        d.control(rule(None, None, None, &[], false)).expect("rule");
        d.control(rule(Some(DEBUG_SOURCE_APPLICATION), Some(DEBUG_TYPE_MARKER), None, &[7], true)).expect("rule");
        marker(&mut d, 7);
        marker(&mut d, 8);
        assert_eq!(d.log.iter().map(|m| m.id).collect::<Vec<_>>(), vec![7]);
        d.control(rule(None, None, None, &[], true)).expect("rule");
        assert_eq!(d.groups[0].rules.len(), 1, "a catch-all rule replaces every older one");
    }

    #[test]
    fn the_log_holds_at_most_its_capacity() {
        let mut d = DebugState { output: true, ..DebugState::default() };
        for i in 0..MAX_LOGGED as u32 + 5 {
            marker(&mut d, i);
        }
        assert_eq!(d.logged(), MAX_LOGGED);
        assert_eq!(d.log.back().map(|m| m.id), Some(MAX_LOGGED as u32 - 1), "later messages are dropped");
    }
}
