//! The bench's permanent record: one CSV row (header written when the file is new) and one JSON object per line
//! (JSON Lines) per run, with the scene, size, device, settings, build options, timings and error figures. The time
//! stamp is the system clock in UTC; nothing is read from version control.

use crate::accuracy::image::ImageError;
use crate::accuracy::TrueError;
use std::fs::OpenOptions;
use std::io::{self, Write};
use std::path::Path;
use std::time::{SystemTime, UNIX_EPOCH};

use fractal_dsl::{HitEpsilon, Scene, Shadows};
use fractal_render::frame::ParamValues;
use fractal_render::select::RendererOptions;
use serde::Serialize;

use super::precision::Deviation;
use super::report::{BenchReport, Stats, Timings};

/// How the program and its kernels were built.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BuildRecord {
    /// `release` or `debug` (host code; the kernels are compiled by the driver either way).
    pub profile: &'static str,
    /// OpenCL build options: `fast-relaxed-math` or `precise` (only the OpenCL backend reads it).
    pub opencl_math: &'static str,
    /// Whether this binary includes the OpenCL backend.
    pub opencl_built: bool,
    pub version: &'static str,
}

impl BuildRecord {
    pub fn current(options: &RendererOptions) -> BuildRecord {
        BuildRecord {
            profile: if cfg!(debug_assertions) { "debug" } else { "release" },
            opencl_math: if options.precise { "precise" } else { "fast-relaxed-math" },
            opencl_built: cfg!(feature = "opencl"),
            version: env!("CARGO_PKG_VERSION"),
        }
    }
    pub fn describe(&self) -> String {
        format!(
            "{} build, OpenCL {}{}",
            self.profile,
            self.opencl_math,
            if self.opencl_built { "" } else { " (OpenCL not built in)" }
        )
    }
}

/// The scene's render settings as recorded.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SettingsRecord {
    pub max_steps: u32,
    pub max_distance: f64,
    /// `fixed <distance>` or `pixel <multiple of the pixel footprint>`.
    pub epsilon: String,
    /// The march's over-relaxation factor ω (1: plain sphere tracing).
    pub over_relaxation: f64,
    /// The normal's taps in pixel footprints, when the scene sets them apart from the hit epsilon.
    pub normal_pixel_epsilon: Option<f64>,
    /// Whether hits are taken on escape-time sets themselves (`membership_hits`).
    pub membership_hits: bool,
    /// `none`, `hard` or `soft <k>`.
    pub shadows: String,
    pub ambient_occlusion: Option<f64>,
    pub glow: Option<[f64; 3]>,
    pub fog_density: Option<f64>,
    pub gamma: f64,
    pub lights: usize,
    /// Parameter values, `name=value`.
    pub params: Vec<String>,
}

impl SettingsRecord {
    pub fn new(scene: &Scene, params: &ParamValues) -> SettingsRecord {
        let s = &scene.settings;
        SettingsRecord {
            max_steps: s.max_steps,
            max_distance: s.max_distance,
            epsilon: match s.epsilon {
                HitEpsilon::Fixed(e) => format!("fixed {e}"),
                HitEpsilon::Pixel(k) => format!("pixel {k}"),
            },
            over_relaxation: s.over_relaxation,
            normal_pixel_epsilon: s.normal_epsilon,
            membership_hits: s.membership_hits,
            shadows: match s.shadows {
                Shadows::None => "none".to_string(),
                Shadows::Hard => "hard".to_string(),
                Shadows::Soft(k) => format!("soft {k}"),
            },
            ambient_occlusion: s.ambient_occlusion,
            glow: s.glow,
            fog_density: s.fog.as_ref().map(|f| f.density),
            gamma: s.gamma,
            lights: scene.effective_lights().len(),
            params: params.decls().iter().zip(params.values()).map(|(d, v)| format!("{}={v}", d.name)).collect(),
        }
    }
}

/// Timings of one kernel as recorded.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimingRecord {
    pub kernel_ms: Stats,
    pub frame_ms: Stats,
    pub fps: f64,
    pub first_frame_ms: f64,
}

impl TimingRecord {
    fn new(t: &Timings) -> TimingRecord {
        TimingRecord { kernel_ms: t.kernel(), frame_ms: t.frame(), fps: t.fps(), first_frame_ms: t.first_frame_ms }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BaselineRecord {
    pub timings: TimingRecord,
    pub error: Option<Deviation>,
    /// generated / baseline, median kernel time.
    pub kernel_ratio: f64,
    /// generated / baseline, median frame time.
    pub frame_ratio: f64,
}

/// One bench run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchRecord {
    /// UTC, ISO 8601.
    pub timestamp: String,
    pub unix_time_s: u64,
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub backend: String,
    pub api: String,
    pub device: String,
    pub driver: String,
    pub device_type: String,
    pub frames: usize,
    pub camera: &'static str,
    /// How kernel times were measured (`device-timestamps`, `opencl-profiling`, `wall-clock`, `whole-frame`).
    pub kernel_clock: &'static str,
    pub settings: SettingsRecord,
    pub build: BuildRecord,
    pub generated: TimingRecord,
    /// Error against the f64 interpreter with the same settings (precision).
    pub error: Deviation,
    /// Error against the ground truth.
    pub true_error: TrueError,
    /// Error against the truth of the image, where measured (`--image-error`).
    pub image_error: Option<ImageError>,
    pub baseline: Option<BaselineRecord>,
}

impl BenchRecord {
    pub fn new(report: &BenchReport, scene: &Scene, params: &ParamValues) -> BenchRecord {
        let unix_time_s = SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0);
        let baseline =
            report.baseline.as_ref().zip(report.ratios()).map(|(b, (kernel_ratio, frame_ratio))| BaselineRecord {
                timings: TimingRecord::new(&b.timings),
                error: b.accuracy.clone(),
                kernel_ratio,
                frame_ratio,
            });
        BenchRecord {
            timestamp: utc_timestamp(unix_time_s),
            unix_time_s,
            scene: report.scene_name.clone(),
            width: report.width,
            height: report.height,
            backend: report.device.backend.to_string(),
            api: report.device.api.clone(),
            device: report.device.name.clone(),
            driver: report.device.driver.clone(),
            device_type: report.device.device_type.clone(),
            frames: report.generated.frame_ms.len(),
            camera: report.camera.name(),
            kernel_clock: report.clock.name(),
            settings: SettingsRecord::new(scene, params),
            build: BuildRecord::current(&report.options),
            generated: TimingRecord::new(&report.generated),
            error: report.accuracy.clone(),
            true_error: report.true_error.clone(),
            image_error: report.image_error,
            baseline,
        }
    }

    /// Column names and values of the CSV row, in order.
    pub fn csv_fields(&self) -> Vec<(&'static str, String)> {
        let opt = |v: Option<f64>| v.map(|v| v.to_string()).unwrap_or_default();
        // Times to the microsecond: the clocks resolve no finer in practice, and rows stay readable.
        let ms = |v: f64| format!("{v:.3}");
        let g = &self.generated;
        let b = self.baseline.as_ref();
        let s = &self.settings;
        vec![
            ("timestamp", self.timestamp.clone()),
            ("scene", self.scene.clone()),
            ("width", self.width.to_string()),
            ("height", self.height.to_string()),
            ("backend", self.backend.clone()),
            ("api", self.api.clone()),
            ("device", self.device.clone()),
            ("driver", self.driver.clone()),
            ("device_type", self.device_type.clone()),
            ("profile", self.build.profile.to_string()),
            ("opencl_math", self.build.opencl_math.to_string()),
            ("frames", self.frames.to_string()),
            ("camera", self.camera.to_string()),
            ("kernel_clock", self.kernel_clock.to_string()),
            ("kernel_min_ms", ms(g.kernel_ms.min)),
            ("kernel_median_ms", ms(g.kernel_ms.median)),
            ("kernel_mean_ms", ms(g.kernel_ms.mean)),
            ("kernel_max_ms", ms(g.kernel_ms.max)),
            ("frame_min_ms", ms(g.frame_ms.min)),
            ("frame_median_ms", ms(g.frame_ms.median)),
            ("frame_mean_ms", ms(g.frame_ms.mean)),
            ("frame_max_ms", ms(g.frame_ms.max)),
            ("fps", format!("{:.4}", g.fps)),
            ("first_frame_ms", ms(g.first_frame_ms)),
            ("error_size", format!("{}x{}", self.error.width, self.error.height)),
            ("hit_mismatch", opt(self.error.hit_mismatch)),
            ("mean_colour_difference", opt(self.error.mean_colour_difference)),
            ("max_steps", s.max_steps.to_string()),
            ("max_distance", s.max_distance.to_string()),
            ("epsilon", s.epsilon.clone()),
            ("over_relaxation", s.over_relaxation.to_string()),
            ("normal_pixel_epsilon", opt(s.normal_pixel_epsilon)),
            ("membership_hits", s.membership_hits.to_string()),
            ("shadows", s.shadows.clone()),
            ("ambient_occlusion", opt(s.ambient_occlusion)),
            ("glow", s.glow.map(|c| format!("{} {} {}", c[0], c[1], c[2])).unwrap_or_default()),
            ("fog_density", opt(s.fog_density)),
            ("params", s.params.join(" ")),
            ("baseline_kernel_median_ms", b.map(|b| ms(b.timings.kernel_ms.median)).unwrap_or_default()),
            ("baseline_frame_median_ms", b.map(|b| ms(b.timings.frame_ms.median)).unwrap_or_default()),
            ("kernel_ratio", opt(b.map(|b| b.kernel_ratio))),
            ("frame_ratio", opt(b.map(|b| b.frame_ratio))),
            ("baseline_hit_mismatch", opt(b.and_then(|b| b.error.as_ref()).and_then(|e| e.hit_mismatch))),
            ("true_false_hits", self.true_error.false_hits.to_string()),
            ("true_false_hits_cone", self.true_error.false_hits_cone.to_string()),
            ("true_false_misses", self.true_error.false_misses.to_string()),
            ("true_psnr_db", format!("{:.2}", self.true_error.psnr)),
            ("image_psnr_db", self.image_error.map(|e| format!("{:.2}", e.psnr)).unwrap_or_default()),
            ("image_ssim", self.image_error.map(|e| format!("{:.4}", e.ssim)).unwrap_or_default()),
            ("image_off", opt(self.image_error.map(|e| e.off))),
        ]
    }
}

/// A CSV field, quoted when it holds a comma, quote or line break.
fn csv_field(value: &str) -> String {
    if value.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", value.replace('"', "\"\""))
    } else {
        value.to_string()
    }
}

fn csv_line(values: impl Iterator<Item = String>) -> String {
    values.map(|v| csv_field(&v)).collect::<Vec<_>>().join(",") + "\n"
}

pub fn append_csv(path: &Path, record: &BenchRecord) -> io::Result<()> {
    let fields = record.csv_fields();
    let mut file = OpenOptions::new().create(true).append(true).open(path)?;
    let mut text = String::new();
    if file.metadata()?.len() == 0 {
        text.push_str(&csv_line(fields.iter().map(|(name, _)| name.to_string())));
    }
    text.push_str(&csv_line(fields.into_iter().map(|(_, value)| value)));
    // One write, so concurrent benches appending to the same file do not interleave within a row.
    file.write_all(text.as_bytes())
}

pub fn append_json(path: &Path, record: &BenchRecord) -> io::Result<()> {
    let mut line = serde_json::to_string(record).map_err(io::Error::other)?;
    line.push('\n');
    OpenOptions::new().create(true).append(true).open(path)?.write_all(line.as_bytes())
}

/// `YYYY-MM-DDTHH:MM:SSZ` for seconds since the Unix epoch (proleptic Gregorian calendar, UTC).
pub fn utc_timestamp(unix_seconds: u64) -> String {
    let days = (unix_seconds / 86_400) as i64;
    let secs = unix_seconds % 86_400;
    // Days to civil date (H. Hinnant's algorithm), eras of 400 years starting on 0000-03-01.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z", secs / 3600, secs / 60 % 60, secs % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timestamps_are_utc_calendar_dates() {
        assert_eq!(utc_timestamp(0), "1970-01-01T00:00:00Z");
        assert_eq!(utc_timestamp(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(utc_timestamp(1_709_251_199), "2024-02-29T23:59:59Z");
        assert_eq!(utc_timestamp(4_102_444_800), "2100-01-01T00:00:00Z");
    }

    #[test]
    fn csv_fields_are_quoted_only_when_needed() {
        assert_eq!(csv_field("llvmpipe"), "llvmpipe");
        assert_eq!(csv_field("llvmpipe (LLVM 19, 256 bits)"), "\"llvmpipe (LLVM 19, 256 bits)\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_line(["a".to_string(), "b,c".to_string()].into_iter()), "a,\"b,c\"\n");
    }
}
