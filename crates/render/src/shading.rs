//! Grid shading through `illume-shade`, the hider's [`GridShader`]: the frame's shaders are
//! bound once (parameters parsed, unknown names reported once), then every diced grid is copied
//! into a [`ShadingGrid`] and shaded with the lights that illuminate it. `Surface "null"` skips
//! shading (depth passes keep `Os`).
use crate::imaging::FrameImager;
use crate::rayscene::{self, RayScene};
use crate::slshaders::{shader_warning, SlShaders};
use crate::volumes::{FrameVolumes, GridRelight, VolumeSlot};
use glam::{DMat4, Vec3};
use illume_geom::Grid;
use illume_reyes::{AovLayout, GridShader, PixelBlock, Shaded};
use illume_ri::{Attributes, Diagnostic, Frame};
use illume_shade::{
    displace, shade_surface_with, Displacement, LightCache, ShadingEnv, ShadingGrid, SpecularModel,
    Surface, TextureLookup, WarnOnce,
};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::{Arc, OnceLock};

/// A bound displacement, keyed like the surfaces; `None` when the name is unknown (warned).
type BoundDisplacement = Option<Arc<Displacement>>;

/// A bound surface, or `None` for `Surface "null"`.
type BoundSurface = Option<Arc<Surface>>;

/// Everything shading needs that is the same for every grid of a frame.
pub(crate) struct FrameShading<'a> {
    pub(crate) frame: &'a Frame,
    /// Bound surfaces keyed by the address of the `Arc<Shader>` the attributes share (the frame
    /// keeps those alive, so an address names one shader for the whole frame).
    surfaces: HashMap<usize, BoundSurface>,
    default_surface: Arc<Surface>,
    displacements: HashMap<usize, BoundDisplacement>,
    /// Bound lights, index-aligned with `Frame::lights` (`None` when binding failed).
    pub(crate) lights: Vec<Option<illume_shade::Light>>,
    coordinate_systems: HashMap<String, DMat4>,
    camera_from_world: DMat4,
    screen_from_camera: DMat4,
    ndc_from_camera: DMat4,
    raster_from_camera: DMat4,
    orthographic: bool,
    specular_model: SpecularModel,
    textures: Option<&'a dyn TextureLookup>,
    /// The geometry rays see: built up front when some light traces shadow rays, else on the
    /// first ray a shader casts (see `trace`).
    rays: OnceLock<RayScene>,
    /// `Option "trace" "maxdepth"`.
    pub(crate) trace_max_depth: u32,
    /// The frame number, for per-point random numbers.
    seed: u32,
    /// The camera's clipping planes, for `depth()`.
    clipping: (f32, f32),
    /// `Option "shadow" "bias"`: SL `shadow()` calls that pass no `"bias"` use it.
    shadow_bias: f32,
    /// What SL `option()` reads, and `attribute()` per distinct attribute set (keyed by the
    /// address of the frame's shared `Attributes`).
    options: illume_shade::RenderInfo,
    attribute_info: HashMap<usize, illume_shade::RenderInfo>,
    pub warnings: WarnOnce,
    pub nonfinite: AtomicU64,
    /// Shaders found as `.sl` files on the shader searchpath (they win over the built-ins).
    pub(crate) sl: SlShaders,
    /// The frame's `Imager`, run on each bucket's filtered pixels.
    imager: Option<FrameImager>,
    /// The output variables the displays ask for (none: no records are made).
    pub(crate) aov: AovLayout,
    /// `Atmosphere`/`Interior`/`Exterior` shaders.
    pub(crate) volumes: FrameVolumes,
}

/// Projective camera → screen → NDC → raster maps (RI Spec 3.2 §4.1.1) as matrices, for the
/// shaders' `transform("NDC", P)` (ReflMap, Listing 9.6).
fn projections(frame: &Frame) -> (DMat4, DMat4, DMat4) {
    let p = frame.camera.projection();
    (
        p.screen_from_camera(),
        p.ndc_from_camera(),
        p.raster_from_camera(),
    )
}

/// Binds every built-in surface the frame's primitives name (keyed by the address of their
/// shared `Arc<Shader>`); `.sl` surfaces are bound by [`SlShaders`]. An unknown or bad surface
/// warns and falls back to `default_surface`; `Surface "null"` binds to `None`.
fn bind_surfaces(
    frame: &Frame,
    sl: &SlShaders,
    default_surface: &Arc<Surface>,
    diags: &mut Vec<Diagnostic>,
) -> HashMap<usize, BoundSurface> {
    let mut surfaces: HashMap<usize, BoundSurface> = HashMap::new();
    for prim in &frame.primitives {
        let Some(shader) = prim.attributes.surface.as_ref() else {
            continue;
        };
        let key = Arc::as_ptr(shader) as usize;
        if surfaces.contains_key(&key) || sl.has_surface(shader) {
            continue;
        }
        let bound = if shader.name == "null" {
            None
        } else {
            match illume_shade::surface(&shader.name, &shader.params) {
                Ok((s, warnings)) => {
                    diags.extend(
                        warnings
                            .into_iter()
                            .map(|w| shader_warning(shader, "Surface", w)),
                    );
                    Some(Arc::new(s))
                }
                Err(e) => {
                    diags.push(shader_warning(
                        shader,
                        "Surface",
                        format!("{e}; using defaultsurface"),
                    ));
                    Some(default_surface.clone())
                }
            }
        };
        surfaces.insert(key, bound);
    }
    surfaces
}

impl<'a> FrameShading<'a> {
    /// Binds every surface and light of the frame; problems come back as warnings with the
    /// span of the `Surface`/`LightSource` request.
    pub fn new(
        frame: &'a Frame,
        textures: Option<&'a dyn TextureLookup>,
    ) -> (FrameShading<'a>, Vec<Diagnostic>) {
        let mut diags = Vec::new();
        let sl = SlShaders::bind(frame, &mut diags);
        let imager = FrameImager::bind(frame, &mut diags);
        let volumes = FrameVolumes::bind(frame, &mut diags);
        let default_surface = Arc::new(Surface::default_surface());
        let surfaces = bind_surfaces(frame, &sl, &default_surface, &mut diags);
        let mut displacements: HashMap<usize, BoundDisplacement> = HashMap::new();
        for prim in &frame.primitives {
            let Some(shader) = prim.attributes.displacement.as_ref() else {
                continue;
            };
            let key = Arc::as_ptr(shader) as usize;
            if displacements.contains_key(&key) || sl.has_displacement(shader) {
                continue;
            }
            let bound = match illume_shade::displacement(&shader.name, &shader.params) {
                Ok((d, warnings)) => {
                    diags.extend(
                        warnings
                            .into_iter()
                            .map(|w| shader_warning(shader, "Displacement", w)),
                    );
                    Some(Arc::new(d))
                }
                Err(e) => {
                    diags.push(shader_warning(
                        shader,
                        "Displacement",
                        format!("{e}; not displacing"),
                    ));
                    None
                }
            };
            displacements.insert(key, bound);
        }
        let lights: Vec<Option<illume_shade::Light>> = frame
            .lights
            .iter()
            .enumerate()
            .map(|(index, l)| {
                let s = &l.shader;
                if sl.has_light(index) {
                    return None;
                }
                match illume_shade::light(&s.name, &s.params, s.camera_from_shader) {
                    Ok((light, warnings)) => {
                        let mut light = light.with_raytraced_shadows(l.shadows);
                        if l.area {
                            let e = rayscene::emitter(frame, index);
                            if !e.is_empty() {
                                light = light.with_emitter(Arc::new(e), l.samples);
                            }
                        }
                        diags.extend(
                            warnings
                                .into_iter()
                                .map(|w| shader_warning(s, "LightSource", w)),
                        );
                        Some(light)
                    }
                    Err(e) => {
                        diags.push(shader_warning(
                            s,
                            "LightSource",
                            format!("{e}; the light is ignored"),
                        ));
                        None
                    }
                }
            })
            .collect();
        let needs_rays = lights.iter().flatten().any(illume_shade::Light::needs_rays);
        let (screen_from_camera, ndc_from_camera, raster_from_camera) = projections(frame);
        let specular_model =
            SpecularModel::from_option(&frame.options.specular_model).unwrap_or_default();
        let shading = FrameShading {
            frame,
            surfaces,
            default_surface,
            displacements,
            lights,
            coordinate_systems: frame.coordinate_systems.iter().cloned().collect(),
            camera_from_world: frame.camera.camera_from_world,
            screen_from_camera,
            ndc_from_camera,
            raster_from_camera,
            orthographic: !frame.camera.is_perspective(),
            specular_model,
            textures,
            rays: OnceLock::new(),
            trace_max_depth: frame.options.trace_max_depth,
            seed: frame.number.unwrap_or(0) as u32,
            clipping: (frame.camera.near as f32, frame.camera.far as f32),
            // PRMan draws each lookup's bias between bias0 and bias1; one value, their mean,
            // keeps the result deterministic.
            shadow_bias: 0.5 * (frame.options.shadow_bias[0] + frame.options.shadow_bias[1]),
            options: crate::renderinfo::options(frame),
            attribute_info: {
                let mut m = HashMap::new();
                for p in &frame.primitives {
                    m.entry(Arc::as_ptr(&p.attributes) as usize)
                        .or_insert_with(|| crate::renderinfo::attributes(&p.attributes));
                }
                m
            },
            warnings: WarnOnce::new(),
            nonfinite: AtomicU64::new(0),
            sl,
            imager,
            aov: AovLayout::default(),
            volumes,
        };
        if needs_rays {
            let scene = shading.build_ray_scene(true);
            let _ = shading.rays.set(scene);
        }
        (shading, diags)
    }

    /// The geometry rays see, built on first use (sequentially: this may run inside a shading
    /// task, see `trace`).
    pub(crate) fn ray_scene(&self) -> &RayScene {
        self.rays.get_or_init(|| self.build_ray_scene(false))
    }

    /// Casters are displaced like the grids the camera sees, so a displaced surface casts its
    /// displaced shadow. Their displacement shaders run without a ray tracer (the scene they
    /// would trace is the one being built).
    fn build_ray_scene(&self, parallel: bool) -> RayScene {
        let displaced = |prim: usize, grid: &Grid| {
            // Casters are displaced like the grids the camera sees, so a displaced surface
            // casts its displaced shadow.
            let attrs = &self.frame.primitives[prim].attributes;
            let flip = self.frame.primitives[prim].normal_sign();
            self.displaced_positions_with(grid, attrs, flip, prim, false)
        };
        RayScene::build(self.frame, &displaced, parallel)
    }

    fn displacement_for(&self, attrs: &Attributes) -> BoundDisplacement {
        let d = attrs.displacement.as_ref()?;
        self.displacements
            .get(&(Arc::as_ptr(d) as usize))
            .cloned()
            .flatten()
    }

    /// Runs the primitive's displacement on `g` (a `.sl` of that name first, else the built-in)
    /// with "shader" space the Displacement's; `false` when it has none.
    fn run_displacement(&self, g: &mut ShadingGrid, attrs: &Attributes, env: &ShadingEnv) -> bool {
        let mut denv = *env;
        if let Some(s) = attrs.displacement.as_ref() {
            denv.camera_from_shader = s.camera_from_shader;
        }
        if let Some(d) = self.sl.displacement(attrs) {
            d.displace(g, &denv);
        } else if let Some(d) = self.displacement_for(attrs) {
            displace(&d, g, &denv);
        } else {
            return false;
        }
        true
    }

    /// The grid's positions after its displacement shader, or `None` when the primitive has
    /// none (for the ray-traced shadow casters, which are diced apart from the hider's grids).
    pub fn displaced_positions(
        &self,
        grid: &Grid,
        attrs: &Attributes,
        flip: f32,
        prim: usize,
    ) -> Option<Vec<Vec3>> {
        self.displaced_positions_with(grid, attrs, flip, prim, true)
    }

    fn displaced_positions_with(
        &self,
        grid: &Grid,
        attrs: &Attributes,
        flip: f32,
        prim: usize,
        tracing: bool,
    ) -> Option<Vec<Vec3>> {
        if self.sl.displacement(attrs).is_none() && self.displacement_for(attrs).is_none() {
            return None;
        }
        let mut g = self.shading_grid(grid, attrs, flip);
        let mut env = self.env(attrs, prim);
        if !tracing {
            env.tracer = None;
        }
        self.run_displacement(&mut g, attrs, &env).then_some(g.p)
    }

    /// The grid as the shaders see it: normals oriented by `flip`, `Cs`/`Os` from primitive
    /// variables or the attributes.
    fn shading_grid(&self, grid: &Grid, attrs: &Attributes, flip: f32) -> ShadingGrid {
        let n = grid.len();
        let mut g = ShadingGrid::new(grid.nu, grid.nv);
        g.p.clone_from(&grid.p);
        // The user's N is theirs: only Ng and a default N follow the orientation.
        let n_flip = if grid.user_normals { 1.0 } else { flip };
        g.n = grid.n.iter().map(|v| *v * n_flip).collect();
        g.ng = grid.ng.iter().map(|v| *v * flip).collect();
        g.dpdu.clone_from(&grid.dpdu);
        g.dpdv.clone_from(&grid.dpdv);
        g.u.clone_from(&grid.u);
        g.v.clone_from(&grid.v);
        g.s.clone_from(&grid.s);
        g.t.clone_from(&grid.t);
        g.du = grid.du;
        g.dv = grid.dv;
        g.cs = grid
            .cs
            .clone()
            .unwrap_or_else(|| vec![Vec3::from(attrs.color); n]);
        g.os = grid
            .os
            .clone()
            .unwrap_or_else(|| vec![Vec3::from(attrs.opacity); n]);
        for var in &grid.vars {
            g.set_var(&var.name, var.components, var.data.clone());
        }
        g.set_incident_from_p(self.orthographic);
        g
    }

    /// The shading environment of frame primitive `prim`, "shader" space the surface's.
    pub(crate) fn env(&self, attrs: &Attributes, prim: usize) -> ShadingEnv<'_> {
        let mut env = self.frame_env();
        let camera_from_shader = attrs
            .surface
            .as_ref()
            .map_or(DMat4::IDENTITY, |s| s.camera_from_shader);
        env.camera_from_object = camera_from_shader;
        env.camera_from_shader = camera_from_shader;
        if let Some(r) = self.rays.get() {
            env.occlusion = Some(r);
            env.ray_offset = r.offset(prim);
        }
        env.primitive = prim;
        env.attributes = self
            .attribute_info
            .get(&(attrs as *const Attributes as usize));
        env
    }

    /// What every shader of the frame shares (spaces, textures, options, warnings): the whole
    /// environment of an imager, which belongs to no primitive.
    pub(crate) fn frame_env(&self) -> ShadingEnv<'_> {
        let mut env = ShadingEnv::new();
        env.camera_from_world = self.camera_from_world;
        env.coordinate_systems = Some(&self.coordinate_systems);
        env.screen_from_camera = self.screen_from_camera;
        env.ndc_from_camera = self.ndc_from_camera;
        env.raster_from_camera = self.raster_from_camera;
        env.specular_model = self.specular_model;
        env.textures = self.textures;
        env.warnings = Some(&self.warnings);
        env.tracer = Some(self);
        env.seed = self.seed;
        env.clipping = self.clipping;
        env.shadow_bias = self.shadow_bias;
        env.options = Some(&self.options);
        env
    }

    fn surface_for(&self, attrs: &Attributes) -> BoundSurface {
        match attrs.surface.as_ref() {
            None => Some(self.default_surface.clone()),
            Some(s) => self
                .surfaces
                .get(&(Arc::as_ptr(s) as usize))
                .cloned()
                .unwrap_or_else(|| Some(self.default_surface.clone())),
        }
    }

    /// Shades one grid of frame primitive `prim`. `flip` (±1) orients the geometric normals as
    /// the attributes say.
    ///
    /// "object" space is not yet carried with the primitive, so shaders see the surface's shader
    /// space there (the same space unless the Surface was declared under another transform).
    pub fn shade_grid(&self, grid: &Grid, attrs: &Attributes, flip: f32, prim: usize) -> Shaded {
        self.shade_grid_at(grid, attrs, flip, prim, None)
    }

    /// A `trace()` hit as a one-point grid, shaded at ray depth `depth` with incident vector
    /// `incident` (the ray): its `Ci`, `Oi`. Not displaced again (the tessellation already is).
    pub(crate) fn shade_hit(
        &self,
        grid: &Grid,
        attrs: &Attributes,
        flip: f32,
        prim: usize,
        depth: u32,
        incident: Vec3,
    ) -> (Vec3, Vec3) {
        let s = self.shade_grid_at(grid, attrs, flip, prim, Some((depth, incident)));
        let at = |v: &[Vec3]| v.first().copied().unwrap_or(Vec3::ZERO);
        (at(&s.ci), at(&s.oi))
    }

    /// [`FrameShading::shade_grid`], or for a ray hit (`ray`: depth and incident vector).
    fn shade_grid_at(
        &self,
        grid: &Grid,
        attrs: &Attributes,
        flip: f32,
        prim: usize,
        ray: Option<(u32, Vec3)>,
    ) -> Shaded {
        let sl_surface = self.sl.surface(attrs);
        let surface = match sl_surface {
            Some(_) => Some(self.default_surface.clone()),
            None => self.surface_for(attrs),
        };
        let Some(surface) = surface else {
            let os = grid
                .os
                .clone()
                .unwrap_or_else(|| vec![Vec3::from(attrs.opacity); grid.len()]);
            // Depth passes (shadow maps) still see the displaced surface.
            let p = self
                .displaced_positions(grid, attrs, flip, prim)
                .unwrap_or_else(|| grid.p.clone());
            return Shaded {
                p,
                ci: vec![Vec3::ZERO; grid.len()],
                oi: os,
                aov: vec![0.0; grid.len() * self.aov.stride],
            };
        };
        let mut g = self.shading_grid(grid, attrs, flip);
        if let Some((_, incident)) = ray {
            g.i = vec![incident; g.len()];
        }
        let lights: Vec<&illume_shade::Light> = attrs
            .lights
            .iter()
            .filter_map(|&i| self.lights.get(i).and_then(Option::as_ref))
            .collect();
        let mut env = self.env(attrs, prim);
        match ray {
            Some((depth, _)) => env.ray_depth = depth,
            None => {
                self.run_displacement(&mut g, attrs, &env);
            }
        }
        let mut cache = LightCache::run(&lights, &g, &env);
        let builtin_count = cache.lights.len();
        let mut sl_outputs = Vec::new();
        // Message passing (RI 3.2 §15.6): SL lights read the SL surface's parameters and the
        // SL surface reads the SL displacement's, as bound for this grid (before they run).
        let to_lights = illume_slvm::Messages {
            surface: sl_surface.map_or(Vec::new(), |s| s.parameter_values(&g, &env)),
            ..Default::default()
        };
        for (proxy, samples, outputs) in self.sl.run_lights(&attrs.lights, &g, &env, &to_lights) {
            cache.lights.push((proxy, samples));
            sl_outputs.push(outputs);
        }
        // SL outputs a display names, filled by the SL surface as it runs.
        let mut sl_wanted: Vec<(&str, Vec<f32>)> = match sl_surface {
            Some(_) => self
                .aov
                .channels
                .iter()
                .map(|c| (c.name.as_str(), Vec::new()))
                .collect(),
            None => Vec::new(),
        };
        let mut view = illume_slvm::Lights::from_cache(&cache);
        for (light, outputs) in view.lights[builtin_count..].iter_mut().zip(&sl_outputs) {
            if let illume_slvm::LightSource::Builtin(request) = light.source {
                light.source = illume_slvm::LightSource::Sl { outputs, request };
            }
        }
        let mut nonfinite = match sl_surface {
            Some(s) => {
                let to_surface = illume_slvm::Messages {
                    displacement: self
                        .sl
                        .displacement(attrs)
                        .map_or(Vec::new(), |d| d.parameter_values(&g, &env)),
                    atmosphere: self.volumes.atmosphere_messages(attrs, &g, &env),
                    ..Default::default()
                };
                s.shade_surface_outputs(&mut g, &view, &env, to_surface, &mut sl_wanted)
                    .nonfinite
            }
            None => shade_surface_with(&surface, &mut g, &cache, &env).nonfinite,
        };
        // The built-in material's components times the `Oi` the surface left: taken before the
        // atmosphere, which changes only `Ci`/`Oi` (PRMan: AOVs are what the surface wrote).
        let components = (sl_surface.is_none() && self.aov.wants_components())
            .then(|| illume_shade::surface_components(&surface, &g, &cache, &env).times(&g.oi));
        let shadow = self
            .aov
            .channels
            .iter()
            .any(|c| c.name == "__shadow")
            .then(|| cache.shadow(g.len()));
        // The atmosphere attenuates what the surface left, before the hider composites.
        let relight = GridRelight {
            builtin: &lights,
            sl: &self.sl,
            indices: &attrs.lights,
            env: &env,
            messages: &to_lights,
        };
        nonfinite += self.volumes.volume_along(
            attrs,
            VolumeSlot::Atmosphere,
            &mut g,
            &env,
            &view,
            Some(&relight),
            None,
        );
        // Records after the atmosphere: `Ci` and `Oi` are what the hider composites; the
        // components and SL outputs are the surface's own.
        let aov = if self.aov.stride == 0 {
            Vec::new()
        } else {
            crate::aov::records(
                &self.aov,
                &g,
                components.as_ref(),
                shadow.as_deref(),
                &sl_wanted,
            )
        };
        if nonfinite > 0 {
            self.nonfinite.fetch_add(nonfinite as u64, Relaxed);
        }
        Shaded {
            p: g.p,
            ci: g.ci,
            oi: g.oi,
            aov,
        }
    }
}

/// The hider's view of the frame's shaders.
impl GridShader for FrameShading<'_> {
    fn shade_grid(&self, grid: &Grid, attrs: &Attributes, flip: f32, prim: usize) -> Shaded {
        FrameShading::shade_grid(self, grid, attrs, flip, prim)
    }

    fn image(&self, block: &mut PixelBlock) {
        if let Some(imager) = &self.imager {
            let nonfinite = imager.run(block, &self.frame_env());
            if nonfinite > 0 {
                self.nonfinite.fetch_add(nonfinite as u64, Relaxed);
            }
        }
    }
}
