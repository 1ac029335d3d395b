//! A deterministic, seeded stream of realistic GLES commands (state changes, uniforms, draws,
//! small uploads) for load tests, the sample client and benchmarks.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use strata_protocol::wire::{Blob, Slice, Text};
use strata_protocol::Command;

/// A seeded generator of commands.
pub struct Workload {
    rng: StdRng,
    bytes: Vec<u8>,
    floats: Vec<f32>,
    names: Vec<u32>,
    max_upload: usize,
}

impl Workload {
    /// A generator whose uploads are at most `max_upload` bytes.
    pub fn new(seed: u64, max_upload: usize) -> Self {
        let mut rng = StdRng::seed_from_u64(seed);
        let bytes = (0..max_upload.max(1)).map(|_| rng.random()).collect();
        let floats = (0..64).map(|_| rng.random_range(-1.0..1.0)).collect();
        Workload { rng, bytes, floats, names: (1..=16).collect(), max_upload }
    }

    /// The next command.
    pub fn next_command(&mut self) -> Command<'_> {
        let r = &mut self.rng;
        match r.random_range(0..12u32) {
            0 => Command::Uniform4f {
                location: r.random_range(0..16),
                x: r.random(),
                y: r.random(),
                z: r.random(),
                w: r.random(),
            },
            1 => Command::DrawArrays { mode: 0x0004, first: r.random_range(0..100), count: r.random_range(3..3000) },
            2 => Command::BindBuffer { target: 0x8892, buffer: r.random_range(0..64) },
            3 => Command::Enable { cap: [0x0B71, 0x0B44, 0x0BE2][r.random_range(0..3)] },
            4 => Command::Viewport { x: 0, y: 0, width: r.random_range(1..1920), height: r.random_range(1..720) },
            5 => Command::VertexAttribPointer {
                index: r.random_range(0..8),
                size: r.random_range(1..5),
                attrib_type: 0x1406,
                normalized: r.random(),
                stride: r.random_range(0..64),
                offset: r.random_range(0..4096),
            },
            6 => {
                let n = r.random_range(0..=self.max_upload);
                let start = r.random_range(0..=self.bytes.len() - n);
                Command::BufferSubData {
                    target: 0x8892,
                    offset: r.random_range(0..1 << 20),
                    data: Blob::borrowed(&self.bytes[start..start + n]),
                }
            }
            7 => Command::UniformMatrix4fv {
                location: r.random_range(0..16),
                transpose: false,
                values: Slice::new(&self.floats[..16]),
            },
            8 => Command::DrawElements { mode: 0x0004, count: r.random_range(3..30000), index_type: 0x1403, offset: 0 },
            9 => Command::GenBuffers { names: Slice::new(&self.names[..r.random_range(1..16)]) },
            10 => {
                Command::ShaderSource { shader: 3, source: Text::borrowed("void main() { gl_FragColor = vec4(1.0); }") }
            }
            _ => Command::Clear { mask: 0x4100 },
        }
    }
}
