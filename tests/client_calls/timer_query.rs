//! `GL_EXT_disjoint_timer_query` through the C entry points: elapsed-time queries around draws
//! and timestamp counters before and after them, whose values (device times, which differ
//! between runs and implementations) are logged as the relations GL guarantees; the state
//! queries; 32- and 64-bit results; and the errors of every call.

use super::*;

const TIME_ELAPSED: u32 = 0x88BF;
const TIMESTAMP: u32 = 0x8E28;
const ANY_SAMPLES: u32 = 0x8C2F;
const CURRENT_QUERY: u32 = 0x8865;
const COUNTER_BITS: u32 = 0x8864;
const RESULT: u32 = 0x8866;
const AVAILABLE: u32 = 0x8867;
const GPU_DISJOINT: u32 = 0x8FBB;
const FLOAT: u32 = 0x1406;

const VS: &str = "attribute vec4 pos; void main() { gl_Position = pos; }";
const FS: &str = "precision mediump float; void main() { gl_FragColor = vec4(0.3, 0.6, 0.9, 1.0); }";

impl Run {
    /// Logs `glGetQueryivEXT(target, pname)`; a current query as whether it is `name` (each
    /// library names queries its own way).
    fn query_iv(&mut self, what: &str, target: u32, pname: u32, name: Option<u32>) {
        let mut v = -1;
        // SAFETY: a context is current; room for one value.
        unsafe { (self.gl.get_query_iv)(target, pname, &mut v) };
        match name {
            Some(n) => self.note(&format!("{what} is it: {}", v == n as i32)),
            None => self.note(&format!("{what} = {v}")),
        }
    }

    /// `id`'s 64-bit result, waited for.
    fn result64(&mut self, id: u32) -> u64 {
        let mut v = 0;
        // SAFETY: a context is current; room for one value.
        unsafe { (self.gl.get_query_object_ui64v)(id, RESULT, &mut v) };
        v
    }
}

/// The timer query sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; every pointer is valid for the call.
    unsafe {
        r.program(VS, FS);
        let mut q = [0u32; 5];
        (gl.gen_queries)(5, q.as_mut_ptr());
        r.query_iv("elapsed counter bits", TIME_ELAPSED, COUNTER_BITS, None);
        r.query_iv("timestamp counter bits", TIMESTAMP, COUNTER_BITS, None);
        r.query_iv("current timestamp query", TIMESTAMP, CURRENT_QUERY, None);
        r.query_iv("current elapsed query before", TIME_ELAPSED, CURRENT_QUERY, None);
        let mut v = -1;
        (gl.get_integerv)(GPU_DISJOINT, &mut v);
        r.note(&format!("disjoint {v}"));
        // Mesa held to ES 2.0 does not answer GL_TIMESTAMP_EXT here.
        let mut now = -1i64;
        (gl.get_integer64v)(TIMESTAMP, &mut now);
        r.note(&format!("the device's time: written {}", now != -1));
        (gl.get_integer64v)(0x0B71, &mut now);
        r.note(&format!("a state as 64 bits: {now}"));

        // The draws below once, finished, before anything is timed: so that neither side times
        // its first use of the program (Mesa's first elapsed time otherwise falls outside its
        // counters when this sequence runs first).
        let quad = [-1.0f32, -1.0, 0.0, 1.0, 1.0, -1.0, 0.0, 1.0, -1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0];
        (gl.bind_buffer)(0x8892, 0);
        (gl.vertex_attrib_pointer)(0, 4, FLOAT, 0, 0, quad.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.draw_arrays)(0x0005, 0, 4);
        (gl.finish)();
        r.note("a draw before timing");

        // A counter, an elapsed time around draws, and a counter.
        (gl.query_counter)(q[0], TIMESTAMP);
        r.note("counter before");
        (gl.begin_query)(TIME_ELAPSED, q[1]);
        r.note("begin elapsed");
        r.query_iv("current elapsed query while active", TIME_ELAPSED, CURRENT_QUERY, Some(q[1]));
        (gl.begin_query)(TIME_ELAPSED, q[3]);
        r.note("a second elapsed query while one is active");
        (gl.query_counter)(q[1], TIMESTAMP);
        r.note("a counter on the active query");
        let mut u = 0u32;
        (gl.get_query_object_uiv)(q[1], AVAILABLE, &mut u);
        r.note("the active query's availability");
        for _ in 0..50 {
            (gl.draw_arrays)(0x0005, 0, 4);
        }
        (gl.end_query)(TIME_ELAPSED);
        r.note("end elapsed");
        (gl.query_counter)(q[2], TIMESTAMP);
        r.note("counter after");
        r.query_iv("current elapsed query after", TIME_ELAPSED, CURRENT_QUERY, None);

        let (before, elapsed, after) = (r.result64(q[0]), r.result64(q[1]), r.result64(q[2]));
        r.note(&format!(
            "results: elapsed above 0 {}, counters in order {}, the elapsed time within them {}",
            elapsed > 0,
            before <= after,
            elapsed <= after - before.min(after),
        ));
        for (i, id) in [q[0], q[1], q[2]].into_iter().enumerate() {
            let (mut a, mut i32v, mut u32v, mut i64v) = (0u32, 0i32, 0u32, 0i64);
            (gl.get_query_object_uiv)(id, AVAILABLE, &mut a);
            (gl.get_query_object_iv)(id, RESULT, &mut i32v);
            (gl.get_query_object_uiv)(id, RESULT, &mut u32v);
            (gl.get_query_object_i64v)(id, RESULT, &mut i64v);
            let full = r.result64(id);
            r.note(&format!(
                "query {i}: available {a}, 64-bit signed agrees {}, 32-bit results saturate {} {}",
                i64v as u64 == full,
                i64::from(i32v) == (full.min(i32::MAX as u64) as i64),
                u64::from(u32v) == full.min(u64::from(u32::MAX)),
            ));
        }
        r.note(&format!("a counter is a query: {}", (gl.is_query)(q[0])));

        // The errors.
        (gl.begin_query)(TIMESTAMP, q[3]);
        r.note("begin on the timestamp target");
        (gl.query_counter)(q[3], TIME_ELAPSED);
        r.note("a counter on the elapsed target");
        (gl.query_counter)(0, TIMESTAMP);
        r.note("a counter on query 0");
        (gl.query_counter)(999, TIMESTAMP);
        r.note("a counter on a name never generated");
        (gl.begin_query)(TIME_ELAPSED, q[0]);
        r.note("an elapsed query on a counter");
        (gl.begin_query)(ANY_SAMPLES, q[1]);
        r.note("an occlusion query on an elapsed query");
        (gl.query_counter)(q[1], TIMESTAMP);
        r.note("a counter on an elapsed query");
        (gl.end_query)(TIME_ELAPSED);
        r.note("end with none active");
        let mut u = 0u32;
        (gl.get_query_object_uiv)(q[4], RESULT, &mut u);
        r.note("the result of a query never begun");
        (gl.get_query_object_uiv)(q[0], 0x1234, &mut u);
        r.note("a bad pname");
        r.query_iv("a bad pname of the elapsed target", TIME_ELAPSED, 0x1234, None);
        // Deleting the active query ends it.
        (gl.begin_query)(TIME_ELAPSED, q[3]);
        (gl.delete_queries)(1, &q[3]);
        r.query_iv("current elapsed query after deleting it", TIME_ELAPSED, CURRENT_QUERY, None);
        (gl.delete_queries)(5, q.as_ptr());
        r.note("done");
    }
}
