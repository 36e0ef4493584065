# Builds the check scene from res://config.json and shows each shot in turn. For every shot it prints
# "SHOT <name>" and waits until the page sets window.shot_done = "<name>" (the page screenshots the canvas).
# Shots: probe (flat unshaded ALBEDO on a full-view quad), cube_front / cube_back (the cube alone), a (fractal alone),
# b (cube in front of the fractal), c (cube behind it).
extends Node3D

var cfg: Dictionary
var fractal: MeshInstance3D
var cube: MeshInstance3D
var probe: MeshInstance3D
var cam: Camera3D

func flat(colour: Color) -> ShaderMaterial:
	# An unshaded flat colour given as the shader's ALBEDO (linear, as Godot expects).
	var sh := Shader.new()
	sh.code = "shader_type spatial;\nrender_mode unshaded;\nuniform vec3 c;\nvoid fragment() { ALBEDO = c; }\n"
	var m := ShaderMaterial.new()
	m.shader = sh
	m.set_shader_parameter("c", Vector3(colour.r, colour.g, colour.b))
	return m

func v3(a: Array) -> Vector3:
	return Vector3(a[0], a[1], a[2])

func _ready() -> void:
	cfg = JSON.parse_string(FileAccess.get_file_as_string("res://config.json"))
	print("GODOT_VERSION ", Engine.get_version_info().string, " renderer ", RenderingServer.get_current_rendering_method(),
		" adapter ", RenderingServer.get_video_adapter_name())
	var env := Environment.new()
	env.background_mode = Environment.BG_COLOR
	env.background_color = Color(1, 0, 1)  # magenta: a colour the fractal does not take
	env.tonemap_mode = Environment.TONE_MAPPER_LINEAR
	env.tonemap_exposure = 1.0
	env.tonemap_white = 1.0
	var we := WorldEnvironment.new()
	we.environment = env
	add_child(we)

	# Scene coordinates are left-handed y-up; Godot's right-handed: mirror z.
	var m := Vector3(1, 1, -1)
	cam = Camera3D.new()
	cam.keep_aspect = Camera3D.KEEP_HEIGHT  # fov is vertical
	cam.fov = cfg.fov
	cam.near = 0.05
	cam.far = cfg.far
	add_child(cam)
	var pos := v3(cfg.camera_pos) * m
	var target := v3(cfg.camera_target) * m
	cam.look_at_from_position(pos, target, Vector3.UP)

	var lo := v3(cfg.bound_min)
	var hi := v3(cfg.bound_max)
	var box := BoxMesh.new()
	box.size = hi - lo
	fractal = MeshInstance3D.new()
	fractal.mesh = box
	fractal.position = (lo + hi) * 0.5 * m
	var mat := ShaderMaterial.new()
	mat.shader = load("res://" + cfg.shader)
	fractal.material_override = mat
	add_child(fractal)

	# The occluder: a green unshaded cube, in front of the bound or behind it (placed by prep.py).
	var cb := BoxMesh.new()
	cube = MeshInstance3D.new()
	cube.mesh = cb
	cube.material_override = flat(Color(0, 1, 0))
	add_child(cube)

	# The probe: a quad filling the view, ALBEDO = config.probe (linear), to see what reaches the canvas.
	var q := QuadMesh.new()
	q.size = Vector2(100, 100)
	probe = MeshInstance3D.new()
	probe.mesh = q
	var pc: Array = cfg.probe
	probe.material_override = flat(Color(pc[0], pc[1], pc[2]))
	cam.add_child(probe)
	probe.position = Vector3(0, 0, -1)

	for shot in ["probe", "cube_front", "cube_back", "a", "b", "c"]:
		await show_shot(shot)
	print("ALL_DONE")

func place_cube(spec: Dictionary) -> void:
	# In the camera's frame, dist ahead, offset in units of dist·tan(fov/2); turned a little to show three faces.
	var d := float(spec.dist)
	var k := d * tan(deg_to_rad(cam.fov) / 2)
	var local := Transform3D(Basis.from_euler(Vector3(0.4, 0.6, 0)), Vector3(spec.offset[0] * k, spec.offset[1] * k, -d))
	cube.global_transform = cam.global_transform * local
	(cube.mesh as BoxMesh).size = Vector3.ONE * float(spec.size)

func show_shot(shot: String) -> void:
	probe.visible = shot == "probe"
	fractal.visible = shot in ["a", "b", "c"]
	cube.visible = shot in ["cube_front", "cube_back", "b", "c"]
	if shot in ["cube_front", "b"]:
		place_cube(cfg.cube_front)
	if shot in ["cube_back", "c"]:
		place_cube(cfg.cube_back)
	# A few frames so that the shader is compiled and the frame presented.
	for i in 4:
		await RenderingServer.frame_post_draw
	print("SHOT ", shot)
	while str(JavaScriptBridge.eval("window.shot_done || ''")) != shot:
		await get_tree().process_frame
