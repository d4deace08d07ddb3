# The frames' scene in Godot 4.6 (aliasing.frames, Godot's page): read res://job.json, build the
# ground and boxes, the Camera3D and the DirectionalLight3D with the job's settings, draw one frame
# whose every pixel is the raw shadow factor of the sun (a spatial shader whose light() adds
# ATTENUATION), and hand it with the camera's and light's transforms and projection to the page
# (window.godotDone, through JavaScriptBridge); along a camera path (job.path) the camera then moves to
# each pose and each pose's frame and transforms come back too.
extends Node3D

const LIGHT_KEYS = ["directional_shadow_split_1", "directional_shadow_split_2", "directional_shadow_split_3",
	"directional_shadow_blend_splits", "directional_shadow_fade_start", "directional_shadow_max_distance",
	"directional_shadow_pancake_size", "shadow_bias", "shadow_normal_bias", "shadow_blur", "shadow_reverse_cull_face",
	"light_angular_distance"]
const MODES = {"SHADOW_ORTHOGONAL": DirectionalLight3D.SHADOW_ORTHOGONAL,
	"SHADOW_PARALLEL_2_SPLITS": DirectionalLight3D.SHADOW_PARALLEL_2_SPLITS,
	"SHADOW_PARALLEL_4_SPLITS": DirectionalLight3D.SHADOW_PARALLEL_4_SPLITS}
const SIZE = "rendering/lights_and_shadows/directional_shadow/size"
const BITS = "rendering/lights_and_shadows/directional_shadow/16_bits"
const QUALITY = "rendering/lights_and_shadows/directional_shadow/soft_shadow_filter_quality"

const FACTOR_SHADER = """
shader_type spatial;
render_mode ambient_light_disabled, specular_disabled, diffuse_lambert, %s;
void fragment() { ALBEDO = vec3(1.0); }
void light() { DIFFUSE_LIGHT += vec3(ATTENUATION); }
"""


func _vec(a) -> Vector3:
	return Vector3(float(a[0]), float(a[1]), float(a[2]))


func _done(result: Dictionary) -> void:
	var text := JSON.stringify(result)
	var window = JavaScriptBridge.get_interface("window")
	if window == null:
		print("GODOT_DONE " + text)
	else:
		window.godotDone(text)


func _ready() -> void:
	var t0 := Time.get_ticks_msec()
	var f := FileAccess.open("res://job.json", FileAccess.READ)
	var job = JSON.parse_string(f.get_as_text())
	var s: Dictionary = job["settings"]
	# the scene: one triangle soup, flat normals; Godot's front faces wind clockwise, the job's counter-clockwise
	var raw := Marshalls.base64_to_raw(job["triangles"]).to_float32_array()
	var verts := PackedVector3Array()
	var normals := PackedVector3Array()
	for t in range(0, raw.size(), 9):
		var a := Vector3(raw[t], raw[t + 1], raw[t + 2])
		var b := Vector3(raw[t + 3], raw[t + 4], raw[t + 5])
		var c := Vector3(raw[t + 6], raw[t + 7], raw[t + 8])
		var n := (b - a).cross(c - a).normalized()
		verts.append_array([a, c, b])
		normals.append_array([n, n, n])
	var arrays := []
	arrays.resize(Mesh.ARRAY_MAX)
	arrays[Mesh.ARRAY_VERTEX] = verts
	arrays[Mesh.ARRAY_NORMAL] = normals
	var mesh := ArrayMesh.new()
	mesh.add_surface_from_arrays(Mesh.PRIMITIVE_TRIANGLES, arrays)
	var shader := Shader.new()
	shader.code = FACTOR_SHADER % ("cull_disabled" if s.get("double_sided", false) else "cull_back")
	var mat := ShaderMaterial.new()
	mat.shader = shader
	var inst := MeshInstance3D.new()
	inst.mesh = mesh
	inst.material_override = mat
	add_child(inst)

	var cam := Camera3D.new()
	var c: Dictionary = job["camera"]
	cam.fov = float(c["fov"])
	cam.near = float(c["near"])
	cam.far = float(c["far"])
	add_child(cam)
	cam.look_at_from_position(_vec(c["eye"]), _vec(c["target"]), _vec(c["up"]))
	cam.make_current()

	var light := DirectionalLight3D.new()
	light.shadow_enabled = true
	light.light_energy = float(job.get("energy", 1.0))
	light.directional_shadow_mode = MODES[s.get("directional_shadow_mode", "SHADOW_PARALLEL_4_SPLITS")]
	for key in LIGHT_KEYS:
		if s.has(key):
			light.set(key, s[key])
	add_child(light)
	var sun := _vec(job["sun"])
	var up := Vector3.UP if abs(sun.y) < 0.999 else Vector3.FORWARD
	light.look_at_from_position(Vector3.ZERO, -sun, up)
	RenderingServer.set_default_clear_color(Color(0.0, 0.0, 1.0))  # blue: no surface (the factor is grey)
	RenderingServer.directional_shadow_atlas_set_size(int(s.get(SIZE, 4096)), bool(s.get(BITS, true)))
	RenderingServer.directional_soft_shadow_filter_set_quality(int(s.get(QUALITY, 2)))

	for i in range(int(job.get("settle", 2))):
		await RenderingServer.frame_post_draw
	var t1 := Time.get_ticks_msec()
	var img := get_viewport().get_texture().get_image()
	img.convert(Image.FORMAT_RGBA8)
	var result := {
		"engine": "godot", "version": Engine.get_version_info()["string"],
		"renderer": RenderingServer.get_video_adapter_name(), "method": ProjectSettings.get_setting("rendering/renderer/rendering_method"),
		"width": img.get_width(), "height": img.get_height(), "factor": Marshalls.raw_to_base64(img.get_data()),
		"frame": "data:image/png;base64," + Marshalls.raw_to_base64(img.save_png_to_buffer()),
		"camera_transform": _xform(cam.global_transform), "light_transform": _xform(light.global_transform),
		"projection": _projection(cam), "light": _light(light), "ms_setup": t1 - t0,
	}
	# a camera path: the camera itself moves to each pose (Godot fits its directional shadow to the current
	# camera only); each pose's frame is read back after `settle` frames, and the page keeps the shadow data
	# Godot uploaded for it (window.godotPose)
	var poses = job.get("path")
	if poses != null:
		var window = JavaScriptBridge.get_interface("window")
		var frames := []
		for pose in poses:
			cam.look_at_from_position(_vec(pose["eye"]), _vec(pose["target"]), _vec(c["up"]))
			for i in range(int(job.get("settle", 2))):
				await RenderingServer.frame_post_draw
			var pimg := get_viewport().get_texture().get_image()
			pimg.convert(Image.FORMAT_RGBA8)
			if window != null:
				window.godotPose()
			frames.append({"factor": Marshalls.raw_to_base64(pimg.get_data()), "camera_transform": _xform(cam.global_transform),
				"light_transform": _xform(light.global_transform), "projection": _projection(cam)})
		result["path"] = frames
		result["ms_path"] = Time.get_ticks_msec() - t1
	_done(result)


func _projection(cam: Camera3D) -> Array:
	var p := cam.get_camera_projection()
	var proj := []
	for col in [p.x, p.y, p.z, p.w]:
		proj.append_array([col.x, col.y, col.z, col.w])
	return proj


func _xform(t: Transform3D) -> Array:
	return [t.basis.x.x, t.basis.x.y, t.basis.x.z, t.basis.y.x, t.basis.y.y, t.basis.y.z,
		t.basis.z.x, t.basis.z.y, t.basis.z.z, t.origin.x, t.origin.y, t.origin.z]


func _light(light: DirectionalLight3D) -> Dictionary:
	var out := {"directional_shadow_mode": light.directional_shadow_mode}
	for key in LIGHT_KEYS:
		out[key] = light.get(key)
	return out
