//! Fuzzing the recording reader (what `coupler replay` reads first): thousands of mutated
//! recordings — cuts, bit flips, frame lengths set to 0, 2³¹ and 2³²−1, bincode lengths inside a
//! frame set to 2⁶⁴−1, random bytes — from a fixed seed. Every case must come back without a panic
//! either as an error saying why, or as the frames before the damage with the damage named; a
//! version-2 frame that comes back is always the frame that was written (its CRC-32C catches the
//! change); and no read allocates more than the bound stated in `schemas::recording`:
//! the frame's bytes (never more than the file holds) plus max(1 MiB, 1024 × frame length).

use schemas::link::bincode_config;
use schemas::message::{Checkpoint, Fields, FromParticipant, Header, ToParticipant, Waveform};
use schemas::recording::{Frame, Message, Recorder, Recording, RecordingEnd, RecordingHeader, MAGIC_V1};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Counts live heap bytes and their peak, so a test can bound what one call allocates.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(now, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(now, Ordering::Relaxed);
        System.alloc_zeroed(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// xorshift64*: a fixed-seed generator, so every run fuzzes the same cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn header() -> RecordingHeader {
    RecordingHeader {
        protocol: 1,
        case_hash: 0xfeed,
        case_path: "cases/oscillator/case.toml".into(),
        case_text: "[case]\nname = \"fuzz\"\nend_time = 1.0\n".repeat(20),
        run_id: "fuzz-1".into(),
        participants: vec!["fluid".into(), "box".into()],
    }
}

/// A run's frames: requests and answers with bodies' forces and poses at four samples.
fn frames() -> Vec<Frame> {
    let mut out = Vec::new();
    for w in 0..6u64 {
        let h = Header {
            protocol: 1,
            window: w,
            iteration: 0,
            time: 0.01 * (w + 1) as f64,
        };
        let f = Fields {
            body_force: (0..12)
                .map(|i| i as f64 * 0.5 + w as f64)
                .collect::<Vec<_>>()
                .into(),
            ..Fields::default()
        };
        let times = vec![0.0, 0.003, 0.006, 0.01];
        out.push(Frame {
            participant: "box".into(),
            wall_time: w as f64,
            message: Message::To(ToParticipant::Advance {
                header: h,
                checkpoint: Checkpoint::None,
                inputs: Waveform::constant(times.clone(), &f),
            }),
        });
        let g = Fields {
            body_pose: (0..14).map(|i| (i as f64).sin()).collect::<Vec<_>>().into(),
            ..Fields::default()
        };
        out.push(Frame {
            participant: "box".into(),
            wall_time: w as f64 + 0.5,
            message: Message::From(FromParticipant::Advanced {
                header: h,
                outputs: Waveform::constant(times, &g),
                geometry: None,
            }),
        });
    }
    out.push(Frame {
        participant: String::new(),
        wall_time: 9.0,
        message: Message::RunEnded {
            window: Some(6),
            reason: "participant `fluid` in window 6: killed by signal 9 (SIGKILL)".into(),
        },
    });
    out
}

/// The same run as a version-2 recording (through [`Recorder`]) and as a version-1 one.
fn recordings() -> (Vec<u8>, Vec<u8>) {
    let path = std::env::temp_dir().join(format!("recording-fuzz-{}.rec", std::process::id()));
    let mut rec = Recorder::create(&path, &header()).unwrap_or_else(|e| panic!("{e}"));
    for f in frames() {
        rec.record(&f.participant, f.wall_time, f.message)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    drop(rec);
    let v2 = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let _ = std::fs::remove_file(&path);
    let mut v1 = MAGIC_V1.to_vec();
    let mut push = |payload: Vec<u8>| {
        v1.extend_from_slice(&(payload.len() as u32).to_le_bytes());
        v1.extend_from_slice(&payload);
    };
    push(bincode::encode_to_vec(header(), bincode_config()).unwrap_or_default());
    for f in frames() {
        push(bincode::encode_to_vec(f, bincode_config()).unwrap_or_default());
    }
    (v2, v1)
}

/// Byte offsets of the length fields of every frame (header included).
fn frame_starts(bytes: &[u8], version: u32) -> Vec<usize> {
    let prefix = if version == 2 { 8 } else { 4 };
    let mut at = MAGIC_V1.len();
    let mut starts = Vec::new();
    while at + prefix <= bytes.len() {
        starts.push(at);
        let len = u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize;
        at += prefix + len;
    }
    starts
}

/// Reads one mutated recording and checks what comes back; returns the peak extra heap bytes.
fn read_checked(bytes: &[u8], version: u32, original: &[Frame], what: &str) -> usize {
    let base = LIVE.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    let result = Recording::from_bytes(bytes);
    let peak = PEAK.load(Ordering::Relaxed).saturating_sub(base);
    match &result {
        Err(why) => assert!(!why.is_empty(), "{what}: an error must say why"),
        Ok(rec) => {
            assert!(
                rec.frames.len() <= original.len(),
                "{what}: more frames than written"
            );
            // A file cut exactly between two frames reads as a shorter whole one: the reader cannot
            // tell, and replay says where such a run ended (no `Finished` at its end).
            if rec.frames.len() < original.len() && !what.ends_with("between frames") {
                assert_ne!(rec.end, RecordingEnd::Whole, "{what}: frames lost without a word");
            }
            assert!(!rec.end.to_string().is_empty());
            if version == 2 {
                for (i, (got, want)) in rec.frames.iter().zip(original).enumerate() {
                    assert_eq!(got, want, "{what}: frame {} came back changed", i + 1);
                }
            }
        }
    }
    peak
}

/// Sets the u32 length field at `at`.
fn set_len(bytes: &mut [u8], at: usize, len: u32) {
    bytes[at..at + 4].copy_from_slice(&len.to_le_bytes());
}

/// Overwrites 9 bytes at `at` with bincode's varint for 2⁶⁴−1 (a `Vec` or `String` length).
fn huge_varint(bytes: &mut [u8], at: usize) {
    let n = bytes.len().saturating_sub(at).min(9);
    let varint = [0xfd, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff];
    bytes[at..at + n].copy_from_slice(&varint[..n]);
}

/// Recomputes a version-2 frame's CRC, so that a mutation inside it reaches the decoder.
fn reseal(bytes: &mut [u8], start: usize) {
    let len =
        u32::from_le_bytes([bytes[start], bytes[start + 1], bytes[start + 2], bytes[start + 3]]) as usize;
    let end = (start + 8 + len).min(bytes.len());
    let crc = crc32c::crc32c(&bytes[start + 8..end]);
    bytes[start + 4..start + 8].copy_from_slice(&crc.to_le_bytes());
}

#[test]
fn thousands_of_mutated_recordings_read_without_panic_within_the_allocation_bound() {
    let (v2, v1) = recordings();
    let original = frames();
    assert_eq!(
        Recording::from_bytes(&v2).map(|r| r.frames.len()).ok(),
        Some(original.len())
    );
    assert_eq!(
        Recording::from_bytes(&v1).map(|r| r.frames.len()).ok(),
        Some(original.len())
    );
    // The stated bound for these recordings: every frame is under 1 KiB, so the decoder's containers
    // are limited to 1 MiB; add the file's own length for the frame bytes read.
    let bound = (1 << 20) + 2 * v2.len().max(v1.len());
    let mut rng = Rng(0x5eed_2026_1123);
    let mut cases = 0;
    let mut worst = 0;
    for (base, version) in [(&v2, 2u32), (&v1, 1u32)] {
        let starts = frame_starts(base, version);
        // `exact`: frames that come back must be the ones written (false where a test reseals a
        // changed frame on purpose).
        let mut read = |bytes: &[u8], exact: bool, what: String| {
            let checked_as = if exact { version } else { 1 };
            worst = worst.max(read_checked(bytes, checked_as, &original, &what));
            cases += 1;
        };
        // Every cut.
        for len in 0..base.len() {
            let between = if starts.contains(&len) {
                " between frames"
            } else {
                ""
            };
            read(&base[..len], true, format!("v{version} cut at {len}{between}"));
        }
        // Each frame's length set to 0, 2³¹, 2³²−1 (a u32 field's 2⁶⁴−1) and ±1.
        for &start in &starts {
            let len = u32::from_le_bytes([base[start], base[start + 1], base[start + 2], base[start + 3]]);
            for claim in [0, 1 << 31, u32::MAX, len.wrapping_add(1), len.wrapping_sub(1)] {
                let mut b = base.clone();
                set_len(&mut b, start, claim);
                read(&b, true, format!("v{version} frame at {start} claiming {claim}"));
            }
        }
        // Bit flips: one to eight at random places.
        for _ in 0..3000 {
            let mut b = base.clone();
            for _ in 0..1 + rng.below(8) {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
            read(&b, true, format!("v{version} bit flips"));
        }
        // A length inside a frame set to 2⁶⁴−1, the frame resealed so the decoder sees it.
        for _ in 0..1000 {
            let mut b = base.clone();
            let k = rng.below(starts.len());
            let prefix = if version == 2 { 8 } else { 4 };
            let at = starts[k] + prefix + rng.below(40);
            if at < b.len() {
                huge_varint(&mut b, at);
            }
            if version == 2 {
                reseal(&mut b, starts[k]);
            }
            read(&b, false, format!("v{version} a huge inner length in frame {k}"));
        }
        // Random bytes after the magic line, and random bytes alone.
        for n in 0..300 {
            let mut b = base[..MAGIC_V1.len()].to_vec();
            b.extend((0..rng.below(2000)).map(|_| rng.next() as u8));
            read(&b, true, format!("v{version} random body {n}"));
            let noise: Vec<u8> = (0..rng.below(200)).map(|_| rng.next() as u8).collect();
            read(&noise, true, format!("noise {n}"));
        }
    }
    println!(
        "{cases} mutated recordings read; the largest extra heap in one read: {worst} bytes (bound {bound})"
    );
    assert!(cases > 5000, "{cases} cases");
    assert!(
        worst <= bound,
        "a read allocated {worst} bytes, above the bound {bound}"
    );
}
