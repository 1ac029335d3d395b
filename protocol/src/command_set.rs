//! The generator behind the command table: one `macro_rules!` expansion yields the `Command`
//! enum, `Opcode`, `Reply`, the typed `Calls` methods, (with `arbitrary`) test strategies and
//! `arbitrary::Arbitrary` commands for fuzzing, and `command_table!`, which hands the same table
//! to a macro of another crate (the daemon derives its dispatch from it).

/// What the command table says of a command besides its fields and reply, written in
/// brackets after its name (`glBufferData [Context, Flush] => ...`); the daemon's dispatch reads these
/// rather than keeping lists of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Attribute {
    /// It acts on the current context (every GL call), and does nothing without one.
    Context,
    /// It needs no current context (EGL calls, Strata's own).
    NoContext,
    /// It writes a buffer or texture that a draw already recorded may read, so the daemon
    /// submits the pending pass before it.
    Flush,
    /// It is OpenGL ES 3.0's: in an ES 2.0 context it does nothing but record
    /// `GL_INVALID_OPERATION`, as Mesa's dispatch answers an entry point its context lacks.
    Es3,
}

impl Attribute {
    /// Whether `attributes` state exactly one of [`Attribute::Context`] and
    /// [`Attribute::NoContext`]: the table's rule, checked when it compiles.
    pub const fn states_context(attributes: &[Attribute]) -> bool {
        let (mut context, mut none, mut i) = (0, 0, 0);
        while i < attributes.len() {
            match attributes[i] {
                Attribute::Context => context += 1,
                Attribute::NoContext => none += 1,
                Attribute::Flush | Attribute::Es3 => {}
            }
            i += 1;
        }
        context + none == 1
    }
}

/// Expands the command table (see `commands.rs`) into every derived item.
macro_rules! command_set {
    (
        async {
            $( $(#[doc = $adoc:literal])* $agl:ident [ $($aat:ident),+ ] => $av:ident { $( $af:ident : $aty:ty ),* $(,)? } ; )*
        }
        sync {
            $( $(#[doc = $sdoc:literal])* $sgl:ident [ $($sat:ident),+ ] => $sv:ident { $( $sf:ident : $sty:ty ),* $(,)? } -> $ret:ty ; )*
        }
    ) => {
        /// Hands the whole command table to `$callback!`, in the form
        /// `async { glName [Attribute, ...] => Variant { field: Type, ... }; ... }
        /// sync { glName [Attribute, ...] => Variant { field: Type, ... } -> ReplyType; ... }`,
        /// so that another crate can derive code from it (a dispatch, a trait) and cannot
        /// miss a command. The field types name `strata_protocol::wire` and
        /// `strata_protocol::commands` items, which the caller brings into scope.
        #[macro_export]
        macro_rules! command_table {
            ($callback:ident) => {
                $callback! {
                    async { $( $agl [ $($aat),+ ] => $av { $( $af : $aty ),* } ; )* }
                    sync { $( $sgl [ $($sat),+ ] => $sv { $( $sf : $sty ),* } -> $ret ; )* }
                }
            };
        }

        // Every command states whether it needs a current context: one that states nothing
        // does not compile.
        $( const _: () = assert!(
            crate::Attribute::states_context(&[ $( crate::Attribute::$aat ),+ ]),
            concat!(stringify!($agl), " must state exactly one of [Context] and [NoContext]")
        ); )*
        $( const _: () = assert!(
            crate::Attribute::states_context(&[ $( crate::Attribute::$sat ),+ ]),
            concat!(stringify!($sgl), " must state exactly one of [Context] and [NoContext]")
        ); )*

        /// One call a client streams to the daemon, decoded in place from the ring.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
        #[serde(bound(deserialize = "'de: 'a"))]
        #[allow(missing_docs)]
        pub enum Command<'a> {
            $( #[doc = concat!("`", stringify!($agl), "`, fire-and-forget.")] $(#[doc = $adoc])* $av { $( $af: $aty ),* }, )*
            $( #[doc = concat!("`", stringify!($sgl), "`, answered with a reply.")] $(#[doc = $sdoc])* $sv { $( $sf: $sty ),* }, )*
        }

        /// The number of each command on the wire; its position in the table.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[repr(u16)]
        pub enum Opcode {
            $( #[doc = concat!("`", stringify!($agl), "`")] $av, )*
            $( #[doc = concat!("`", stringify!($sgl), "`")] $sv, )*
        }

        impl Opcode {
            /// Every opcode, in wire order.
            pub const ALL: &'static [Opcode] = &[ $(Opcode::$av,)* $(Opcode::$sv,)* ];
            /// How many commands the protocol defines.
            pub const COUNT: usize = Self::ALL.len();

            /// The EGL/GL entry point's name, e.g. `glDrawArrays`.
            pub fn name(self) -> &'static str {
                match self {
                    $( Opcode::$av => stringify!($agl), )*
                    $( Opcode::$sv => stringify!($sgl), )*
                }
            }

            /// Whether the caller waits for a reply.
            pub fn is_sync(self) -> bool {
                match self {
                    $( Opcode::$av => false, )*
                    $( Opcode::$sv => true, )*
                }
            }

            /// The attributes the table gives this command (`glName [Attribute, ...] => ...`).
            pub fn attributes(self) -> &'static [crate::Attribute] {
                use crate::Attribute::*;
                match self {
                    $( Opcode::$av => &[ $( $aat ),+ ], )*
                    $( Opcode::$sv => &[ $( $sat ),+ ], )*
                }
            }

            /// Whether the command writes a buffer or texture that a recorded draw may read
            /// ([`Attribute::Flush`](crate::Attribute::Flush)).
            pub fn flushes_first(self) -> bool {
                self.attributes().contains(&crate::Attribute::Flush)
            }

            /// Whether the command acts on the current context, and so does nothing without one
            /// ([`Attribute::Context`](crate::Attribute::Context)).
            pub fn needs_context(self) -> bool {
                self.attributes().contains(&crate::Attribute::Context)
            }

            /// Whether the command is OpenGL ES 3.0's ([`Attribute::Es3`](crate::Attribute::Es3)).
            pub fn es3_only(self) -> bool {
                self.attributes().contains(&crate::Attribute::Es3)
            }

            /// The opcode with wire number `index`, if the protocol defines one.
            pub fn from_index(index: u32) -> Option<Opcode> {
                Self::ALL.get(index as usize).copied()
            }
        }

        impl<'a> Command<'a> {
            /// Which command this is.
            pub fn opcode(&self) -> Opcode {
                match self {
                    $( Command::$av { .. } => Opcode::$av, )*
                    $( Command::$sv { .. } => Opcode::$sv, )*
                }
            }

            /// If a blob of the command holds at least `min` bytes: the command with that blob
            /// (the first such) announced as streamed, and the blob's bytes, to be streamed
            /// after it ([`crate::ring::Writer::write_bulk`]).
            pub fn split_bulk(&self, min: usize) -> Option<(Command<'_>, &[u8])> {
                #[allow(unused_imports)]
                use crate::wire::{BulkProbe, BulkProbeAny};
                let mut bulk = None;
                let cmd = match self {
                    $( Command::$av { $( $af ),* } => Command::$av { $( $af: BulkProbe($af).split(min, &mut bulk) ),* }, )*
                    $( Command::$sv { $( $sf ),* } => Command::$sv { $( $sf: BulkProbe($sf).split(min, &mut bulk) ),* }, )*
                };
                bulk.map(|b| (cmd, b))
            }

            /// The command's first streamed blob not yet attached to its stream, if any.
            pub fn bulk_mut(&mut self) -> Option<&mut crate::wire::Blob<'a>> {
                #[allow(unused_imports)]
                use crate::wire::{BulkProbeMut, BulkProbeMutAny};
                match self {
                    $( Command::$av { $( $af ),* } => { $( if let Some(b) = BulkProbeMut($af).streamed() { return Some(b); } )* None } )*
                    $( Command::$sv { $( $sf ),* } => { $( if let Some(b) = BulkProbeMut($sf).streamed() { return Some(b); } )* None } )*
                }
            }
        }

        /// The daemon's answer to a synchronous command: one variant per synchronous call.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        pub enum Reply {
            $( #[doc = concat!("Result of `", stringify!($sgl), "`.")] $sv($ret), )*
            /// The daemon does not implement this call; the text says why.
            Unsupported(String),
        }

        impl Reply {
            /// The command this reply answers, or `None` for `Unsupported`.
            pub fn opcode(&self) -> Option<Opcode> {
                match self {
                    $( Reply::$sv(_) => Some(Opcode::$sv), )*
                    Reply::Unsupported(_) => None,
                }
            }
        }

        /// A reply that does not answer the call it was read for.
        #[derive(Debug, thiserror::Error)]
        #[error("reply mismatch: expected the answer to {}, got {got:?}", expected.name())]
        pub struct ReplyMismatch {
            /// The call that was waiting.
            pub expected: Opcode,
            /// What arrived instead.
            pub got: Reply,
        }

        /// Typed EGL/GLES methods, one per command, over a transport that can send and call.
        #[allow(non_snake_case, clippy::too_many_arguments, clippy::extra_unused_lifetimes, clippy::needless_lifetimes)]
        pub trait Calls {
            /// The transport's error type.
            type Error: From<ReplyMismatch>;
            /// Queues a fire-and-forget command.
            fn send(&mut self, cmd: &Command<'_>) -> Result<(), Self::Error>;
            /// Sends a synchronous command and waits for its reply.
            fn call(&mut self, cmd: &Command<'_>) -> Result<Reply, Self::Error>;

            $(
                #[doc = concat!("Queues `", stringify!($agl), "`.")]
                fn $agl<'a>(&mut self, $( $af: $aty ),*) -> Result<(), Self::Error> {
                    self.send(&Command::$av { $( $af ),* })
                }
            )*
            $(
                #[doc = concat!("Calls `", stringify!($sgl), "` and waits for its result.")]
                fn $sgl<'a>(&mut self, $( $sf: $sty ),*) -> Result<$ret, Self::Error> {
                    match self.call(&Command::$sv { $( $sf ),* })? {
                        Reply::$sv(v) => Ok(v),
                        other => Err(ReplyMismatch { expected: Opcode::$sv, got: other }.into()),
                    }
                }
            )*
        }

        #[cfg(feature = "arbitrary")]
        impl Opcode {
            /// A proptest strategy producing arbitrary commands with this opcode.
            pub fn strategy<'a>(self) -> proptest::strategy::BoxedStrategy<Command<'a>>
            where
                'a: 'static,
            {
                use proptest::prelude::*;
                match self {
                    $( Opcode::$av => (Just(()), $( any::<$aty>(), )*)
                        .prop_map(|((), $( $af, )*)| Command::$av { $( $af ),* })
                        .boxed(), )*
                    $( Opcode::$sv => (Just(()), $( any::<$sty>(), )*)
                        .prop_map(|((), $( $sf, )*)| Command::$sv { $( $sf ),* })
                        .boxed(), )*
                }
            }

            /// A proptest strategy producing arbitrary replies to this opcode (`None` if async).
            pub fn reply_strategy(self) -> Option<proptest::strategy::BoxedStrategy<Reply>> {
                use proptest::prelude::*;
                match self {
                    $( Opcode::$av => None, )*
                    $( Opcode::$sv => Some(any::<$ret>().prop_map(Reply::$sv).boxed()), )*
                }
            }
        }
    };
}

pub(crate) use command_set;
