//! A context's `GL_KHR_debug` state: output on or off, the message log, the callback's pending
//! messages, and the group stack with each group's rules.

use std::collections::VecDeque;

use strata_protocol::commands::DebugMessage;
use strata_protocol::Bytes;

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::{MAX_LOGGED, MAX_PENDING, MAX_RULE_IDS};

/// One `glDebugMessageControlKHR` call: which messages it addresses and what it set.
#[derive(Clone)]
pub(crate) struct Rule {
    /// `None` is `GL_DONT_CARE`.
    pub(crate) source: Option<u32>,
    pub(crate) ty: Option<u32>,
    pub(crate) severity: Option<u32>,
    /// Empty: every id.
    pub(crate) ids: Vec<u32>,
    pub(crate) enabled: bool,
}

impl Rule {
    pub(crate) fn matches(&self, m: &DebugMessage) -> bool {
        self.source.is_none_or(|s| s == m.source)
            && self.ty.is_none_or(|t| t == m.ty)
            && self.severity.is_none_or(|s| s == m.severity)
            && (self.ids.is_empty() || self.ids.contains(&m.id))
    }

    /// Whether every message `older` matches is matched by `self` too.
    pub(crate) fn covers(&self, older: &Rule) -> bool {
        let field = |new: Option<u32>, old: Option<u32>| new.is_none() || new == old;
        field(self.source, older.source)
            && field(self.ty, older.ty)
            && field(self.severity, older.severity)
            && (self.ids.is_empty() || (!older.ids.is_empty() && older.ids.iter().all(|i| self.ids.contains(i))))
    }
}

/// One entry of the debug group stack.
#[derive(Clone)]
pub(crate) struct Group {
    pub(crate) source: u32,
    pub(crate) id: u32,
    pub(crate) text: Vec<u8>,
    pub(crate) rules: Vec<Rule>,
}

/// A context's debug output state.
pub struct DebugState {
    /// `GL_DEBUG_OUTPUT_KHR`.
    pub output: bool,
    /// `GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR`.
    pub synchronous: bool,
    /// Whether the application has a callback (messages go to `pending`, not `log`).
    pub(crate) callback: bool,
    pub(crate) log: VecDeque<DebugMessage>,
    pub(crate) pending: VecDeque<DebugMessage>,
    /// The group stack; the default group is at the bottom and is never popped.
    pub(crate) groups: Vec<Group>,
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

impl DebugState {
    pub(crate) fn enabled(&self, m: &DebugMessage) -> bool {
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

    pub(crate) fn control(&mut self, rule: Rule) -> GlResult {
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
