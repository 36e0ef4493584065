//! Fuzzing the scene language. Random token streams — the built-in scenes' text cut, spliced and sprinkled with the
//! language's words and hostile values, and streams of dictionary tokens with no seed at all — go through the parser
//! as a `.fractal` file would. Whatever the text, the parser must not panic, hang or return an error without a place
//! and a short, escaped message. Whatever it accepts must compile, print back to the same scene, evaluate, and draw
//! the same picture on the CPU and wgpu at 16×16 (the same mask and colour tolerances as `tests/backends.rs`, looser
//! by the share one silhouette pixel is of 256).
//!
//! `FRACTAL_FUZZ_CASES` sets the number of texts (default 20 000: a few seconds), `FRACTAL_FUZZ_RENDERS` how many
//! accepted ones are drawn (default 16) and `FRACTAL_FUZZ_SEED` the seed; `cargo xtask fuzz N` runs N texts and
//! draws 200. The closing line counts texts, accepted texts and renders compared.

use std::time::Instant;

use fractal::dsl::eval::interp::Interpreter;
use fractal::dsl::eval::Env;
use fractal::dsl::number::math::v3;
use fractal::dsl::parse::{parse_str, SourceError};
use fractal::dsl::print::to_source;
use fractal::dsl::{compile, Scene};
use fractal::render::{CpuRenderer, Frame, Image, KernelSources, RenderJob, Renderer, WgpuRenderer};
use fractal::scenes;

const DEFAULT_CASES: u64 = 20_000;
/// Accepted texts drawn on both backends by default: each costs a wgpu pipeline build (up to a second on lavapipe).
const DEFAULT_RENDERS: usize = 16;
const SIZE: u32 = 16;
const CHANNEL_TOLERANCE: u8 = 8;
/// Of 256 pixels, at most 8 may flip hit/miss and 16 differ in colour: a few ulps of a GPU built-in can flip a pixel a
/// silhouette or shadow edge crosses, and at this size one edge crosses a dozen pixels.
const MASK_AGREEMENT: f64 = 0.97;
const COLOUR_AGREEMENT: f64 = 0.93;
/// Longest error message accepted, in bytes: quotations are cut at 64 characters.
const MAX_MESSAGE: usize = 600;

/// Hostile or odd spellings a careless user might type, beside the words the seeds contain.
const HOSTILE: &[&str] = &[
    "0",
    "-0.0",
    "1e308",
    "1e999",
    "-1e308",
    "1e-320",
    "5e-324",
    "0.0 / 0.0",
    "1.0 / 0.0",
    "300u8",
    "3u32",
    "1.0f32",
    "1.5f64",
    "18446744073709551615",
    "4294967296",
    "1_000",
    "0x10",
    "\"text\"",
    "'c'",
    "\0",
    "\u{1b}[2J",
    "é",
    "∞",
    "// comment\n",
    "/* open",
    "*/",
    "#",
    "$",
    "@",
    "?",
    ";",
    "::",
    "=>",
    "..",
    "..=",
    "=",
    "!",
    "&",
    "|",
    "<",
    ">",
    "..",
    "[",
    "]",
    "{",
    "}",
    "(",
    ")",
    ",",
    ".",
    "+",
    "-",
    "*",
    "/",
    "%",
    "t",
    "param(\"p\", 1.0, 0.0..2.0)",
    "\n",
    " ",
    "if",
    "let",
    "fn",
    "self",
    "_",
    // formulas: hostile maps, and the language's own tokens
    "escape_time(|z, c| z / (z.x - z.x) + c)",
    "escape_time(|z, c| z * 0.5).iterations(64)",
    "escape_time(|z, c| pow(z, 1e9) + c).bailout(1e6)",
    "fold(|z| (z * 1e30, 0.0))",
    "fold(|z, c| { let k = 1.0 / dot(z, z); (z * k, ln(k)) })",
    "hybrid(|z| z, |z, c| c)",
    "escape_time(|z, c| if z.x < 0.0 { z.zyx } else { -z } + c)",
    "|z, c|",
    "&&",
    "||",
    "<=",
    "else",
    "vec4(z, 0.0)",
    "qsqr",
    "z.wzyx",
];

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Splits text into tokens: identifiers, numbers (with exponent and suffix), strings, and single other characters.
/// Whitespace is kept as tokens so that positions in errors stay meaningful.
fn tokens(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let start = i;
        let c = chars[i];
        if c.is_alphanumeric() || c == '_' {
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_' || chars[i] == '.') {
                // A `.` continues a number, not a method call on an identifier.
                if chars[i] == '.' && !chars[start].is_ascii_digit() {
                    break;
                }
                i += 1;
            }
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                i += 1;
            }
            i = (i + 1).min(chars.len());
        } else {
            i += 1;
        }
        out.push(chars[start..i].iter().collect());
    }
    out
}

/// The words of every seed (identifiers and numbers) and the hostile spellings.
fn dictionary(seeds: &[Vec<String>]) -> Vec<String> {
    let mut words: Vec<String> = HOSTILE.iter().map(|s| s.to_string()).collect();
    for t in seeds.iter().flatten() {
        if t.chars().next().is_some_and(|c| c.is_alphanumeric()) && !words.contains(t) {
            words.push(t.clone());
        }
    }
    words
}

/// One fuzz text: a seed with 1–4 token edits, or (one time in eight) a stream of dictionary tokens.
fn mutate(rng: &mut Rng, seeds: &[Vec<String>], words: &[String]) -> String {
    if rng.below(8) == 0 {
        let n = 1 + rng.below(40);
        return (0..n).map(|_| rng.pick(words).clone()).collect::<Vec<_>>().join(if rng.below(2) == 0 {
            ""
        } else {
            " "
        });
    }
    let mut t = rng.pick(seeds).clone();
    for _ in 0..1 + rng.below(4) {
        let len = t.len().max(1);
        let at = rng.below(len);
        let span = 1 + rng.below(8.min(len));
        let end = (at + span).min(t.len());
        match rng.below(7) {
            0 => {
                t.drain(at..end);
            }
            1 => {
                let copy: Vec<String> = t[at..end].to_vec();
                let to = rng.below(t.len() + 1);
                t.splice(to..to, copy);
            }
            2 => t.insert(at.min(t.len()), rng.pick(words).clone()),
            3 if !t.is_empty() => {
                let i = at.min(t.len() - 1);
                t[i] = rng.pick(words).clone();
            }
            4 if t.len() > 1 => {
                let (i, other) = (at.min(t.len() - 1), rng.below(t.len()));
                t.swap(i, other);
            }
            5 => {
                // Splice a piece of another seed in.
                let donor = rng.pick(seeds);
                let from = rng.below(donor.len());
                let piece = donor[from..(from + 1 + rng.below(30)).min(donor.len())].to_vec();
                t.splice(at.min(t.len())..end.max(at.min(t.len())), piece);
            }
            _ => {
                // Replace a number with a hostile one.
                let numbers: Vec<usize> =
                    (0..t.len()).filter(|&i| t[i].starts_with(|c: char| c.is_ascii_digit())).collect();
                if !numbers.is_empty() {
                    let i = *rng.pick(&numbers);
                    t[i] = rng.pick(&HOSTILE[..20]).to_string();
                }
            }
        }
    }
    t.concat()
}

fn seeds() -> Vec<Vec<String>> {
    let mut texts: Vec<String> = scenes::ALL.iter().map(|(_, compiled)| to_source(compiled.scene())).collect();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for dir in ["scenes/fractal", "tests/fractal/cli"] {
        let mut files: Vec<_> = std::fs::read_dir(root.join(dir)).unwrap().map(|e| e.unwrap().path()).collect();
        files.sort();
        texts.extend(
            files
                .iter()
                .filter(|p| p.extension().is_some_and(|e| e == "fractal"))
                .map(|p| std::fs::read_to_string(p).unwrap()),
        );
    }
    texts.iter().map(|t| tokens(t)).collect()
}

#[track_caller]
fn check_error(text: &str, e: &SourceError) {
    let lines = text.split('\n').count();
    assert!(!e.message.contains("internal error"), "the parser failed inside on:\n{text}\n{e}");
    assert!(e.line >= 1 && e.line <= lines + 1 && e.column >= 1, "error outside the text ({e}) for:\n{text}");
    assert!(e.message.len() <= MAX_MESSAGE, "a {} byte message for:\n{text}", e.message.len());
    assert!(!e.message.chars().any(|c| c.is_control() && c != '\n'), "a raw control character in {e:?}");
}

#[track_caller]
fn check_accepted(text: &str, scene: &Scene) {
    if let Err(e) = compile(scene) {
        panic!("the parser accepted what compile refuses ({e}):\n{text}");
    }
    let printed = to_source(scene);
    match parse_str(&printed) {
        Ok(again) => assert_eq!(&again, scene, "printing changed the scene:\n{text}\nprinted as\n{printed}"),
        Err(e) => panic!("the printed scene does not parse ({e}):\n{printed}\nfrom\n{text}"),
    }
    let interp = Interpreter::new(scene).expect("compile accepted it");
    let params = interp.default_params::<f64>();
    let env = Env::new(0.0, &params);
    for [x, y, z] in [[0.0, 0.0, 0.0], [0.5, -0.25, 2.0], [1e4, 0.0, -1e4]] {
        interp.distance_in(v3(x, y, z), &env);
    }
}

fn agreement(cpu: &Image, gpu: &Image) -> (f64, f64) {
    let bg = cpu.rgba(0, 0).unwrap();
    let (mut mask, mut colour) = (0usize, 0usize);
    for y in 0..cpu.height {
        for x in 0..cpu.width {
            let (a, b) = (cpu.rgba(x, y).unwrap(), gpu.rgba(x, y).unwrap());
            mask += ((a == bg) == (b == bg)) as usize;
            colour += a.iter().zip(b).all(|(p, q)| p.abs_diff(q) <= CHANNEL_TOLERANCE) as usize;
        }
    }
    let n = (cpu.width * cpu.height) as f64;
    (mask as f64 / n, colour as f64 / n)
}

/// Draws an accepted scene on the CPU and wgpu; `false` when the frame itself is refused (the same on both).
fn render_agrees(text: &str, scene: &Scene, gpu: &mut WgpuRenderer) -> bool {
    let Ok(frame) = Frame::default_view(scene, 0.0, SIZE, SIZE) else { return false };
    let interp = Interpreter::new(scene).unwrap();
    let kernels = compile(scene).unwrap();
    let cpu = CpuRenderer::new().render(&RenderJob::new(KernelSources::default().with_cpu(&interp, scene), &frame));
    let wgpu = gpu.render(&RenderJob::new(KernelSources::compiled(&kernels), &frame));
    let (cpu, wgpu) = match (cpu, wgpu) {
        (Ok(a), Ok(b)) => (a, b),
        (a, b) => panic!("a render failed (cpu {:?}, wgpu {:?}) for:\n{text}", a.err(), b.err()),
    };
    let (mask, colour) = agreement(&cpu, &wgpu);
    assert!(
        mask >= MASK_AGREEMENT && colour >= COLOUR_AGREEMENT,
        "CPU and wgpu differ (mask {mask}, colour {colour}):\n{text}"
    );
    true
}

#[test]
fn random_token_streams_never_break_the_parser_and_accepted_ones_agree_on_every_backend() {
    fn setting<T: std::str::FromStr>(name: &str, default: T) -> T {
        std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
    }
    let cases: u64 = setting("FRACTAL_FUZZ_CASES", DEFAULT_CASES);
    let renders: usize = setting("FRACTAL_FUZZ_RENDERS", DEFAULT_RENDERS);
    let seed: u64 = setting("FRACTAL_FUZZ_SEED", 0x5eed_f00d);
    let seeds = seeds();
    let words = dictionary(&seeds);
    let mut rng = Rng(seed | 1);
    let mut gpu = match WgpuRenderer::new() {
        Ok(gpu) => Some(gpu),
        Err(e) if fractal_render::device::backends_required() => {
            panic!("wgpu required but unavailable: {e}")
        }
        Err(e) => {
            eprintln!("wgpu skipped: {e}");
            None
        }
    };
    let started = Instant::now();
    let (mut accepted, mut rendered) = (0u64, 0usize);
    let mut drawn: Vec<String> = Vec::new();
    for _ in 0..cases {
        let text = mutate(&mut rng, &seeds, &words);
        match parse_str(&text) {
            Err(e) => check_error(&text, &e),
            Ok(scene) => {
                accepted += 1;
                check_accepted(&text, &scene);
                let printed = to_source(&scene);
                if rendered < renders && !drawn.contains(&printed) {
                    if let Some(gpu) = gpu.as_mut() {
                        rendered += render_agrees(&text, &scene, gpu) as usize;
                    }
                    drawn.push(printed);
                }
            }
        }
    }
    eprintln!(
        "fuzz: {cases} texts (seed {seed}), {accepted} accepted, {rendered} drawn on CPU and wgpu, {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(accepted > 0, "no text was accepted: the mutations are too coarse to reach the compiler");
}
