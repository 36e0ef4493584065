//! Export of a scene's render kernel for other engines: OpenCL C and WGSL as the scene compiler wrote them, and
//! GLSL, HLSL, MSL and SPIR-V translated by naga from the WGSL module.
//!
//! Every export holds one compute entry point, `render` ([`ENTRY_POINT`]; GLSL names it `main`), with two resources:
//! the output pixels (a read-write buffer of one `u32` per pixel, row-major, red in the low byte and alpha 255 in the
//! high byte) and the frame uniforms ([`fractal_dsl::back::FrameLayout`] gives their layout, [`fractal_render::Frame`]
//! packs them). In the translated targets and WGSL they are group/set 0, bindings 0 and 1 (the OpenCL kernel takes them
//! as arguments 0 and 1). Workgroups are 8×8×1: dispatch `ceil(width / 8) × ceil(height / 8) × 1`; invocations outside
//! the image return at once.
//!
//! What each translated target is written for, and where the resources go:
//! - GLSL: `#version 450 core` compute shader (OpenGL 4.5 / Vulkan GLSL); `layout(binding = N)` keeps the WGSL
//!   binding numbers: 0 for the pixel buffer block, 1 for the uniform block.
//! - HLSL: shader model 6.0 (`cs_6_0`, DXC / Direct3D 12): the oldest model DXC accepts, and register spaces need
//!   at least 5.1. Group `g`, binding `b` become `register(<class>b, space<g>)` (naga leaves out `space0`): `u0` for
//!   the pixels, `b1` for the uniforms.
//! - MSL: Metal Shading Language 2.0 (macOS 10.13, iOS 11 and later). Buffers take slots in binding order
//!   (`[[buffer(0)]]` pixels, `[[buffer(1)]]` uniforms); the next slot carries the byte sizes of runtime-sized
//!   buffers, which Metal cannot query (the pixel buffer is one).
//! - SPIR-V: version 1.0 (Vulkan 1.0 and later), descriptor set = group, binding = binding, with debug names.
//!
//! Buffer accesses are written without bounds checks (naga's default policy): the kernel guards its only index itself.

use std::fmt;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::str::FromStr;

use fractal_dsl::compiled::{CompiledScene, Kernels};
use fractal_dsl::validate::InvalidScene;
use fractal_dsl::Scene;
use naga::back::{glsl, hlsl, msl, spv};
use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};
use naga::{Module, ResourceBinding, ShaderStage};

/// Name of the compute entry point in every export (GLSL's is always `main`).
pub const ENTRY_POINT: &str = "render";

/// GLSL version written: 450 core.
pub const GLSL_VERSION: u16 = 450;
/// HLSL shader model written: 6.0.
pub const HLSL_SHADER_MODEL: hlsl::ShaderModel = hlsl::ShaderModel::V6_0;
/// Metal Shading Language version written: 2.0.
pub const MSL_VERSION: (u8, u8) = (2, 0);
/// SPIR-V version written: 1.0.
pub const SPIRV_VERSION: (u8, u8) = (1, 0);

/// A language or binary format a scene's render kernel can be exported to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Target {
    /// OpenCL C (kernel `render`), as the OpenCL renderer runs it.
    OpenCl,
    /// WGSL (entry point `render`), as the wgpu renderer runs it.
    Wgsl,
    /// GLSL 450 core compute shader.
    Glsl,
    /// HLSL compute shader, shader model 6.0.
    Hlsl,
    /// Metal Shading Language 2.0 kernel.
    Msl,
    /// SPIR-V 1.0 binary module.
    SpirV,
}

impl Target {
    /// Every target, in the order `--help` lists them.
    pub const ALL: [Target; 6] = [Target::OpenCl, Target::Wgsl, Target::Glsl, Target::Hlsl, Target::Msl, Target::SpirV];

    /// The name the command line and [`FromStr`] use. WGSL, GLSL and HLSL carry `-kernel`: the plain language
    /// names are the function libraries of [`crate::package`].
    pub fn name(self) -> &'static str {
        match self {
            Target::OpenCl => "opencl",
            Target::Wgsl => "wgsl-kernel",
            Target::Glsl => "glsl-kernel",
            Target::Hlsl => "hlsl-kernel",
            Target::Msl => "msl",
            Target::SpirV => "spirv",
        }
    }

    /// The usual file extension, without the dot (`Path::with_extension` takes it so). GLSL's is `comp`, the
    /// extension by which tools such as glslangValidator recognise a compute shader.
    pub fn extension(self) -> &'static str {
        match self {
            Target::OpenCl => "cl",
            Target::Wgsl => "wgsl",
            Target::Glsl => "comp",
            Target::Hlsl => "hlsl",
            Target::Msl => "metal",
            Target::SpirV => "spv",
        }
    }

    /// Whether the export is binary (SPIR-V) rather than text.
    pub fn is_binary(self) -> bool {
        self == Target::SpirV
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A target name that is not one of [`Target::ALL`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown export target `{0}`: expected one of opencl, wgsl-kernel, glsl-kernel, hlsl-kernel, msl, spirv")]
pub struct UnknownTarget(pub String);

impl FromStr for Target {
    type Err = UnknownTarget;

    /// Reads a target name, ignoring ASCII case and surrounding whitespace.
    fn from_str(s: &str) -> Result<Target, UnknownTarget> {
        let wanted = s.trim();
        Target::ALL.into_iter().find(|t| t.name().eq_ignore_ascii_case(wanted)).ok_or_else(|| UnknownTarget(s.into()))
    }
}

/// An exported kernel: source text, or a binary module (SPIR-V words as little-endian bytes).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Exported {
    Text(String),
    Binary(Vec<u8>),
}

impl Exported {
    /// The bytes to write to a file.
    pub fn as_bytes(&self) -> &[u8] {
        match self {
            Exported::Text(text) => text.as_bytes(),
            Exported::Binary(bytes) => bytes,
        }
    }

    /// The text, for a text export.
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Exported::Text(text) => Some(text),
            Exported::Binary(_) => None,
        }
    }

    pub fn into_bytes(self) -> Vec<u8> {
        match self {
            Exported::Text(text) => text.into_bytes(),
            Exported::Binary(bytes) => bytes,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.as_bytes().is_empty()
    }
}

/// Why a kernel could not be exported.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// The scene breaks a rule of the scene language (only scenes not made by the parser can).
    #[error(transparent)]
    InvalidScene(#[from] InvalidScene),
    /// naga's WGSL front end refused the compiler's WGSL: a bug in the WGSL writer.
    #[error("the WGSL kernel does not parse (a scene compiler bug):\n{0}")]
    WgslParse(String),
    /// naga's validator refused the compiler's WGSL: a bug in the WGSL writer.
    #[error("the WGSL kernel does not validate (a scene compiler bug):\n{0}")]
    WgslValidation(String),
    /// The WGSL module has no compute entry point `render`.
    #[error("the WGSL kernel has no compute entry point `{ENTRY_POINT}`")]
    NoEntryPoint,
    /// naga's backend for `target` could not translate the module.
    #[error("naga could not translate the kernel to {target}: {message}")]
    Translation { target: Target, message: String },
}

/// The render kernel of compiled `kernels` in `target`'s language or format.
pub fn export(kernels: &Kernels, target: Target) -> Result<Exported, ExportError> {
    export_sources(&kernels.opencl, &kernels.wgsl, target)
}

/// Validates `scene`, compiles it and exports its render kernel.
pub fn export_scene(scene: &Scene, target: Target) -> Result<Exported, ExportError> {
    export(&fractal_dsl::compile(scene)?, target)
}

/// Exports the kernel a scene was compiled to at build time (`scene!`, `scene_file!`, the built-in scenes).
pub fn export_compiled(scene: &CompiledScene, target: Target) -> Result<Exported, ExportError> {
    export_sources(scene.opencl(), scene.wgsl(), target)
}

fn export_sources(opencl: &str, wgsl: &str, target: Target) -> Result<Exported, ExportError> {
    match target {
        Target::OpenCl => Ok(Exported::Text(opencl.to_owned())),
        Target::Wgsl => Ok(Exported::Text(wgsl.to_owned())),
        Target::Glsl | Target::Hlsl | Target::Msl | Target::SpirV => {
            let (module, info) = parse_and_validate(wgsl)?;
            translate(&module, &info, target)
        }
    }
}

/// The WGSL kernel as a validated naga module with its render entry point.
fn parse_and_validate(wgsl: &str) -> Result<(Module, ModuleInfo), ExportError> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| ExportError::WgslParse(e.emit_to_string(wgsl)))?;
    // Default capabilities: what every backend supports, so a kernel needing more is refused here, by name.
    let info = Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .map_err(|e| ExportError::WgslValidation(e.emit_to_string(wgsl)))?;
    if !module.entry_points.iter().any(|ep| ep.name == ENTRY_POINT && ep.stage == ShaderStage::Compute) {
        return Err(ExportError::NoEntryPoint);
    }
    Ok((module, info))
}

fn translate(module: &Module, info: &ModuleInfo, target: Target) -> Result<Exported, ExportError> {
    let fail = |message: String| ExportError::Translation { target, message };
    // naga's backends assume what validation does not check for every backend (`unreachable!`, `unimplemented!`);
    // such a panic is reported as a failed translation, not passed on to the caller.
    let written = catch_unwind(AssertUnwindSafe(|| match target {
        Target::Glsl => write_glsl(module, info).map(Exported::Text),
        Target::Hlsl => write_hlsl(module, info).map(Exported::Text),
        Target::Msl => write_msl(module, info).map(Exported::Text),
        Target::SpirV => write_spirv(module, info).map(Exported::Binary),
        Target::OpenCl | Target::Wgsl => Err(format!("{target} is not translated by naga")),
    }));
    match written {
        Ok(result) => result.map_err(fail),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".into());
            Err(fail(format!("naga panicked: {what}")))
        }
    }
}

/// The module's resource bindings, in (group, binding) order. The WGSL kernel declares only what `render` uses.
fn bindings(module: &Module) -> Vec<(ResourceBinding, naga::Handle<naga::GlobalVariable>)> {
    let mut bindings: Vec<_> =
        module.global_variables.iter().filter_map(|(handle, var)| var.binding.map(|b| (b, handle))).collect();
    bindings.sort_by_key(|(b, _)| (b.group, b.binding));
    bindings
}

fn write_glsl(module: &Module, info: &ModuleInfo) -> Result<String, String> {
    let mut binding_map = glsl::BindingMap::default();
    // OpenGL has no groups: binding points are numbered in (group, binding) order, which keeps the WGSL numbers of
    // a kernel whose bindings are group 0, numbered from 0 without gaps (as the WGSL writer's are).
    for (index, (binding, _)) in bindings(module).into_iter().enumerate() {
        let point = u8::try_from(index).map_err(|_| format!("{} bindings are more than GLSL's 256", index + 1))?;
        binding_map.insert(binding, point);
    }
    let options = glsl::Options {
        version: glsl::Version::Desktop(GLSL_VERSION),
        writer_flags: glsl::WriterFlags::empty(),
        binding_map,
        zero_initialize_workgroup_memory: true,
    };
    let pipeline =
        glsl::PipelineOptions { shader_stage: ShaderStage::Compute, entry_point: ENTRY_POINT.into(), multiview: None };
    let mut out = String::new();
    let mut writer =
        glsl::Writer::new(&mut out, module, info, &options, &pipeline, naga::proc::BoundsCheckPolicies::default())
            .map_err(|e| e.to_string())?;
    writer.write().map_err(|e| e.to_string())?;
    Ok(out)
}

fn write_hlsl(module: &Module, info: &ModuleInfo) -> Result<String, String> {
    let mut binding_map = hlsl::BindingMap::default();
    for (binding, _) in bindings(module) {
        let space =
            u8::try_from(binding.group).map_err(|_| format!("group {} is beyond HLSL's spaces", binding.group))?;
        binding_map.insert(
            binding,
            hlsl::BindTarget {
                space,
                register: binding.binding,
                binding_array_size: None,
                dynamic_storage_buffer_offsets_index: None,
                restrict_indexing: false,
            },
        );
    }
    let options = hlsl::Options {
        shader_model: HLSL_SHADER_MODEL,
        binding_map,
        fake_missing_bindings: false,
        ..hlsl::Options::default()
    };
    let pipeline = hlsl::PipelineOptions { entry_point: Some((ShaderStage::Compute, ENTRY_POINT.into())) };
    let mut out = String::new();
    let reflection =
        hlsl::Writer::new(&mut out, &options, &pipeline).write(module, info, None).map_err(|e| e.to_string())?;
    for name in reflection.entry_point_names {
        name.map_err(|e| e.to_string())?;
    }
    Ok(out)
}

fn write_msl(module: &Module, info: &ModuleInfo) -> Result<String, String> {
    let mut resources = msl::EntryPointResources::default();
    let mut next_slot: u8 = 0;
    for (binding, handle) in bindings(module) {
        let var = &module.global_variables[handle];
        let mut target = msl::BindTarget::default();
        match module.types[var.ty].inner {
            naga::TypeInner::Image { .. } => target.texture = Some(next_slot),
            naga::TypeInner::Sampler { .. } => target.sampler = Some(msl::BindSamplerTarget::Resource(next_slot)),
            _ => {
                target.buffer = Some(next_slot);
                target.mutable = matches!(var.space, naga::AddressSpace::Storage { access }
                    if access.contains(naga::StorageAccess::STORE));
            }
        }
        resources.resources.insert(binding, target);
        next_slot = next_slot.checked_add(1).ok_or("more than 255 resources")?;
    }
    resources.sizes_buffer = Some(next_slot);
    let options = msl::Options {
        lang_version: MSL_VERSION,
        per_entry_point_map: [(ENTRY_POINT.to_string(), resources)].into_iter().collect(),
        fake_missing_bindings: false,
        ..msl::Options::default()
    };
    let pipeline = msl::PipelineOptions {
        entry_point: Some((ShaderStage::Compute, ENTRY_POINT.into())),
        ..msl::PipelineOptions::default()
    };
    let (text, translation) = msl::write_string(module, info, &options, &pipeline).map_err(|e| e.to_string())?;
    for name in translation.entry_point_names {
        name.map_err(|e| e.to_string())?;
    }
    Ok(text)
}

fn write_spirv(module: &Module, info: &ModuleInfo) -> Result<Vec<u8>, String> {
    let binding_map = bindings(module)
        .into_iter()
        .map(|(b, _)| (b, spv::BindingInfo { descriptor_set: b.group, binding: b.binding, binding_array_size: None }))
        .collect();
    let options = spv::Options {
        lang_version: SPIRV_VERSION,
        binding_map,
        // Names for readable disassembly, the same in debug and release builds (naga's default differs).
        flags: spv::WriterFlags::DEBUG,
        fake_missing_bindings: false,
        ..spv::Options::default()
    };
    let pipeline = spv::PipelineOptions { shader_stage: ShaderStage::Compute, entry_point: ENTRY_POINT.into() };
    let words = spv::write_vec(module, info, &options, Some(&pipeline)).map_err(|e| e.to_string())?;
    Ok(words.iter().flat_map(|w| w.to_le_bytes()).collect())
}
