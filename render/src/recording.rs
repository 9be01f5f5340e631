//! The calls of one frame, as the backends make them: which passes (GLES framebuffers, Vulkan
//! render passes) begin, with which attachments and load operations, what is drawn, what is
//! invalidated, what each pass stores, what a pass samples, what the host reads back. Tests
//! assert on it (the fused paths never store the G-buffer), and the frame's memory traffic is
//! computed from it: the load and store operations and formats the path really used.

/// How a pass starts with an attachment's contents.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Load {
    /// Cleared: nothing is read from memory.
    Clear,
    /// Read from memory.
    Load,
}

/// An attachment of a pass, or a frame texture a pass samples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Attachment {
    /// What it holds: `gbuffer0`, `depth`, `output`...
    pub name: String,
    /// Bytes per pixel of its format.
    pub bytes_per_pixel: u32,
}

/// One recorded call.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Call {
    /// A pass begins over these attachments.
    BeginPass {
        /// The attachments, with how each starts.
        attachments: Vec<(Attachment, Load)>,
    },
    /// A barrier inside the pass: the draws after it read what the draws before it wrote
    /// (Vulkan's by-region barrier between draws).
    Barrier,
    /// A draw with a program (pipeline) of this name.
    Draw {
        /// The program's name.
        program: String,
    },
    /// A pass samples a texture written earlier in the frame (the two-pass G-buffer).
    Sample(Attachment),
    /// Attachments' contents are discarded before the pass ends (glInvalidateFramebuffer).
    Invalidate(Vec<String>),
    /// The pass ends; these attachments are written to memory.
    EndPass {
        /// The attachments stored.
        stored: Vec<String>,
    },
    /// The host reads an attachment back after the frame.
    ReadBack(String),
}

/// The calls of a frame, in order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Recording {
    /// The calls.
    pub calls: Vec<Call>,
}

/// Bytes a frame moves between the GPU and memory, by what its passes load, store and sample
/// (the inputs sampled every frame, the same on every path, are not counted).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Traffic {
    /// Bytes read: attachments loaded, frame textures sampled.
    pub loaded: u64,
    /// Bytes written: attachments stored.
    pub stored: u64,
}

impl Traffic {
    /// Both directions, in the bandwidth units of Arm's article: width x height x 4 bytes.
    pub fn bandwidth_units(self, width: u32, height: u32) -> f64 {
        (self.loaded + self.stored) as f64 / (f64::from(width) * f64::from(height) * 4.0)
    }
}

impl Recording {
    /// Appends a call.
    pub fn push(&mut self, call: Call) {
        self.calls.push(call);
    }

    /// How many passes the frame has.
    pub fn passes(&self) -> usize {
        self.calls
            .iter()
            .filter(|call| matches!(call, Call::BeginPass { .. }))
            .count()
    }

    /// Every attachment stored by some pass, in order.
    pub fn stored(&self) -> Vec<&str> {
        self.calls
            .iter()
            .flat_map(|call| match call {
                Call::EndPass { stored } => stored.iter().map(String::as_str).collect(),
                _ => Vec::new(),
            })
            .collect()
    }

    /// Every attachment invalidated, in order.
    pub fn invalidated(&self) -> Vec<&str> {
        self.calls
            .iter()
            .flat_map(|call| match call {
                Call::Invalidate(names) => names.iter().map(String::as_str).collect(),
                _ => Vec::new(),
            })
            .collect()
    }

    /// The frame's memory traffic at `width` x `height`, from its load and store operations.
    pub fn traffic(&self, width: u32, height: u32) -> Traffic {
        let pixels = u64::from(width) * u64::from(height);
        let mut traffic = Traffic {
            loaded: 0,
            stored: 0,
        };
        let mut attachments: Vec<Attachment> = Vec::new();
        for call in &self.calls {
            match call {
                Call::BeginPass { attachments: list } => {
                    attachments = list
                        .iter()
                        .map(|(attachment, _)| attachment.clone())
                        .collect();
                    for (attachment, load) in list {
                        if *load == Load::Load {
                            traffic.loaded += pixels * u64::from(attachment.bytes_per_pixel);
                        }
                    }
                }
                Call::Sample(texture) => {
                    traffic.loaded += pixels * u64::from(texture.bytes_per_pixel);
                }
                Call::EndPass { stored } => {
                    for name in stored {
                        if let Some(attachment) = attachments.iter().find(|a| &a.name == name) {
                            traffic.stored += pixels * u64::from(attachment.bytes_per_pixel);
                        }
                    }
                }
                _ => {}
            }
        }
        traffic
    }
}
