"""The render settings the add-on offers for its lamps (Cycles' clamp and light tree, EEVEE's shadow pool and ray
tracing), and their restore."""

import bpy

import harness
from addon_common import bake


def test_cycles_settings_offer_and_restore():
    harness.empty_scene()
    scene = bpy.context.scene
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene.cycles.sample_clamp_indirect = 10.0
    has_tree = hasattr(scene.cycles, "use_light_tree")
    if has_tree:
        scene.cycles.use_light_tree = False
    bake(count=64)
    # The measured cost (cycles_clamp.json, render_cost.json): the clamp in 3.4 (no light tree); the light tree
    # switched off in 4.x and later, where the clamp darkens nothing measurable and is not mentioned.
    expected = "indirect clamp (10)" if not has_tree else "light tree is off"
    assert expected in scene.probe_lights.last_warnings, scene.probe_lights.last_warnings
    assert not has_tree or "indirect clamp" not in scene.probe_lights.last_warnings, scene.probe_lights.last_warnings
    assert bpy.ops.probe_lights.cycles_settings() == {"FINISHED"}
    assert scene.cycles.sample_clamp_indirect == 0.0 and (not has_tree or scene.cycles.use_light_tree)
    assert harness.addon_module("cycles_settings").advice(scene, 64) == ""
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert scene.cycles.sample_clamp_indirect == 10.0 and (not has_tree or not scene.cycles.use_light_tree)


def test_eevee_shadow_pool_follows_the_scene_and_restore():
    """EEVEE Next (4.2+) keeps shadows in a pool that about 19 suns fill: a bake in EEVEE makes room by itself,
    without ever shrinking the pool or going past 1 GB, and says so; so does a render in EEVEE of suns baked under
    Cycles; the offer in the panel does it too; Restore world puts the user's values back."""
    harness.empty_scene()
    scene = bpy.context.scene
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene.render.engine = harness.eevee_engine()
    settings = scene.probe_lights
    shadows = harness.addon_module("eevee_settings")
    if bpy.app.version < (4, 2, 0):  # EEVEE Legacy has no shadow pool
        bake(count=64)
        assert "EEVEE" not in settings.last_notes and shadows.advice(scene, 64) == ""
        print("  skipped: EEVEE Legacy (Blender %s) has no shadow pool" % bpy.app.version_string)
        return
    scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale = "512", 1.0
    bake(count=16)  # 16 suns: about 1,900 pages, the default pool holds 2,048
    assert "EEVEE" not in settings.last_notes and not shadows.fitted(scene), settings.last_notes
    bake(count=30)  # about 3,500 pages: a 1 GB pool at full resolution
    assert "EEVEE: shadow pool 1024 MB" in settings.last_notes, settings.last_notes
    assert (scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale) == ("1024", 1.0)
    bake(count=64)  # more than 1 GB holds at full resolution: half resolution in the pool already set
    assert shadows.advice(scene, 64) == "" and shadows.baked_suns(scene) == 64
    assert (scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale) == ("1024", 0.5)
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert (scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale) == ("512", 1.0)
    # Baked under Cycles: the bake fits the pool all the same (EEVEE's settings change no Cycles render, and the
    # file renders right in EEVEE where the add-on is not installed, test_eevee.py); Restore puts it back.
    scene.render.engine = "CYCLES"
    bake(count=30)
    assert shadows.fitted(scene) and scene.eevee.shadow_pool_size == "1024", (
        shadows.fitted(scene), scene.eevee.shadow_pool_size, settings.last_notes)
    assert "EEVEE: shadow pool 1024 MB" in settings.last_notes, settings.last_notes
    assert bpy.ops.probe_lights.restore() == {"FINISHED"} and scene.eevee.shadow_pool_size == "512"
    # The pool set back by hand after a bake, then EEVEE: the panel says what to do in one line, the offer does
    # it, and Restore puts it back.
    bake(count=30)
    shadows.restore(scene)
    assert not shadows.fitted(scene) and scene.eevee.shadow_pool_size == "512"
    scene.render.engine = harness.eevee_engine()
    line = shadows.advice(scene, shadows.baked_suns(scene))
    assert line == ("EEVEE's shadow pool is too small for 30 suns and drops shadows at random: fit the shadows to "
                    "the lamps"), line
    assert bpy.ops.probe_lights.eevee_settings() == {"FINISHED"} and shadows.advice(scene, 30) == ""
    assert bpy.ops.probe_lights.restore() == {"FINISHED"} and scene.eevee.shadow_pool_size == "512"
    scene.eevee.shadow_resolution_scale = 0.75  # between two measured scales: costed as the finer one
    assert shadows._pages(2140, 0.75) == 2354
    scene.eevee.shadow_resolution_scale = 1.0
    scene.render.engine = "CYCLES"


def _cube_lit_by_8_suns():
    """A cube under the bundled probe's world, 8 suns baked (in Cycles): (scene, world, cube, probe_volumes)."""
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.object
    bake(count=8)
    return bpy.context.scene, world, cube, harness.addon_module("probe_volumes")


def test_light_probes_baked_here_are_flagged_when_the_lamps_or_objects_change():
    """After the add-on's bake of EEVEE's light probes (stood in for by what it records after a bake: EEVEE's own
    bake needs OpenGL, test_probe_bake.py bakes for real), the panel says in one line when they no longer hold the
    scene's bounce light, and offers the bake again: the lamps baked again, the world's strength changed (the
    lamps follow it), an object moved, a lamp of the user's added. Not before the add-on's first bake, not outside
    EEVEE. Beside the bake: its cost (the volumes' cells, their bytes in the file, the last bake's seconds)."""
    scene, world, cube, volumes = _cube_lit_by_8_suns()
    if bpy.app.version < (4, 2, 0):
        assert volumes.stale(scene) == ""
        print("  skipped: EEVEE Legacy (Blender %s) bakes no light probe volumes this way" % bpy.app.version_string)
        return
    scene.render.engine = harness.eevee_engine()
    assert volumes.cost(scene) == "The bake adds a volume of 64 cells (5 KB in the file)", volumes.cost(scene)
    bpy.ops.object.lightprobe_add(type="VOLUME")
    assert volumes.stale(scene) == ""  # never baked here: Blender's own bake may have been used
    assert volumes.cost(scene) == "Light probe volume: 64 cells, 5 KB in the file", volumes.cost(scene)
    volumes.remember(scene, 8.25)
    assert volumes.stale(scene) == ""
    assert volumes.cost(scene).endswith("5 KB in the file; the last bake here took 8.2 s"), volumes.cost(scene)
    bpy.context.object.data.resolution_x = 8  # what the panel shows follows the volume's cells
    assert volumes.cost(scene).startswith("Light probe volume: 128 cells, 9 KB"), volumes.cost(scene)
    bake(count=4)
    assert volumes.stale(scene).startswith("The lamps changed since the light probes were baked here")
    volumes.remember(scene, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 2.0
    bpy.context.view_layer.update()  # the lamps' strength drivers
    assert volumes.stale(scene).startswith("The lamps changed"), volumes.stale(scene)
    volumes.remember(scene, 1.0)
    cube.location.x += 0.5
    bpy.context.view_layer.update()
    assert volumes.stale(scene).startswith("The objects changed"), volumes.stale(scene)
    volumes.remember(scene, 1.0)
    own = bpy.data.objects.new("user's lamp", bpy.data.lights.new("user's lamp", "POINT"))
    scene.collection.objects.link(own)  # the user's own lamp bounces light too
    assert volumes.stale(scene).startswith("The lamps changed"), volumes.stale(scene)
    scene.render.engine = "CYCLES"
    assert volumes.stale(scene) == ""  # Cycles bakes no light probes
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}


def test_eevee_ray_tracing_offered_for_the_lamps_bounce_and_restore():
    """EEVEE Next (4.2+) bounces no light by itself, and with all of the light in the lamps reflects none off the
    screen: with baked suns the panel offers what comes closest to Cycles in this Blender
    (blender_caps.eevee_bounce): up to 5.1 its ray tracing alone (and a warning when a light probe volume is there
    too), from 5.2 a volume baked with the lamps and ray tracing; and in both a light probe sphere around the
    scene, which the same button adds (undo takes both back, redo brings them). Restore world turns off the ray
    tracing it turned on and takes the sphere out; ray tracing the user turned on stays on, and then the panel
    offers the sphere alone. Nothing outside EEVEE Next."""
    scene, _, _, volumes = _cube_lit_by_8_suns()
    if bpy.app.version < (4, 2, 0):
        assert volumes.offer(scene) == ""
        print("  skipped: EEVEE Legacy (Blender %s) has no ray tracing to offer" % bpy.app.version_string)
        return
    assert volumes.offer(scene) == ""  # Cycles bounces by itself
    scene.render.engine = harness.eevee_engine()
    scene.eevee.use_raytracing = False
    traced_alone = harness.addon_module("blender_caps").eevee_bounce(bpy.app.version) == "ray tracing"
    offer = volumes.offer(scene)
    assert offer.startswith("EEVEE bounces no light by itself and reflects none of the lamps': turn on its ray "
                            "tracing with a light probe sphere" if traced_alone else
                            "EEVEE bounces no light without a light probe volume"), offer
    assert "ray tracing with a light probe sphere" in offer, offer
    assert not volumes.sphere_probes(scene)
    # As the button runs it (an undo step): undo takes the click back whole, redo brings it back.
    bpy.ops.ed.undo_push(message="before the click")
    assert bpy.ops.probe_lights.eevee_ray_tracing("EXEC_DEFAULT", True) == {"FINISHED"}
    assert bpy.ops.ed.undo() == {"FINISHED"}
    scene = bpy.context.scene  # an undo reloads the data: old references are gone
    assert not scene.eevee.use_raytracing and not volumes.sphere_probes(scene)
    assert bpy.ops.ed.redo() == {"FINISHED"}
    scene = bpy.context.scene
    assert scene.eevee.use_raytracing and len(volumes.sphere_probes(scene)) == 1
    assert bpy.ops.probe_lights.eevee_ray_tracing() == {"FINISHED"}  # nothing more to do
    assert scene.eevee.use_raytracing
    [sphere] = volumes.sphere_probes(scene)
    assert sphere.get(harness.addon_module("light_objects").VOLUME_TAG)
    cube = next(o for o in scene.objects if o.type == "MESH")
    far = max((cube.matrix_world @ v.co - sphere.location).length for v in cube.data.vertices)
    assert far <= sphere.data.influence_distance <= 1.2 * far, (far, sphere.data.influence_distance)
    assert volumes.offer(scene) == "" if traced_alone else volumes.offer(scene).endswith("with the lamps"), \
        volumes.offer(scene)
    bpy.ops.object.lightprobe_add(type="VOLUME")  # a volume with ray tracing: too much up to 5.1, best from 5.2
    assert volumes.offer(scene).endswith("turn one off") if traced_alone else volumes.offer(scene) == "", \
        volumes.offer(scene)
    bpy.data.objects.remove(bpy.context.object)
    assert bpy.ops.probe_lights.eevee_ray_tracing() == {"FINISHED"}  # again
    assert len(volumes.sphere_probes(scene)) == 1
    done = harness.addon_module("bake").restore_world(scene, scene.world)
    assert "EEVEE ray tracing back" in done and not scene.eevee.use_raytracing, done
    assert not volumes.sphere_probes(scene)
    # The user's own ray tracing is the user's: a bake and its restore leave it on. Up to 5.1 that bounces as it
    # should: the panel offers the sphere alone.
    scene.eevee.use_raytracing = True
    bake(count=8)
    if traced_alone:
        assert volumes.offer(scene) == volumes.REFLECTIONS, volumes.offer(scene)
        assert bpy.ops.probe_lights.eevee_ray_tracing(ray_tracing=False) == {"FINISHED"}
        assert volumes.offer(scene) == "" and len(volumes.sphere_probes(scene)) == 1
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert scene.eevee.use_raytracing
    scene.eevee.use_raytracing = False
    scene.render.engine = "CYCLES"


def _material(name, *shaders):
    """A material whose node tree holds the shader nodes `shaders` (bl_idname) and its output."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    for node in [n for n in nodes if n.type != "OUTPUT_MATERIAL"]:
        nodes.remove(node)
    for shader in shaders:
        nodes.new(shader)
    return material


def test_a_light_probe_sphere_only_where_something_reflects():
    """A light probe sphere changes no render of a scene where nothing reflects sharply and slows it (the sphere
    over a plane, all Diffuse BSDF: docs/results/eevee_rivals.md): there the panel offers EEVEE's ray tracing
    alone and its button adds no sphere, saying why. An object without a material, a Principled BSDF, a Glossy
    BSDF inside a node group, or a reflecting material override on the view layer each make the scene reflect."""
    scene, _, cube, volumes = _cube_lit_by_8_suns()
    if bpy.app.version < (4, 2, 0):
        print("  skipped: EEVEE Legacy (Blender %s) has no ray tracing to offer" % bpy.app.version_string)
        return
    scene.render.engine = harness.eevee_engine()
    scene.eevee.use_raytracing = False
    assert volumes.scene_reflects(scene)  # no material: the engines' default surface reflects
    matte = _material("matte", "ShaderNodeBsdfDiffuse", "ShaderNodeEmission", "ShaderNodeMixShader")
    cube.data.materials.append(matte)
    assert not volumes.scene_reflects(scene)
    offer = volumes.offer(scene)
    assert "ray tracing" in offer and "sphere" not in offer and "reflects" not in offer, offer
    assert bpy.ops.probe_lights.eevee_ray_tracing() == {"FINISHED"}
    assert scene.eevee.use_raytracing and not volumes.sphere_probes(scene)
    traced_alone = harness.addon_module("blender_caps").eevee_bounce(bpy.app.version) == "ray tracing"
    assert volumes.offer(scene) == "" if traced_alone else volumes.offer(scene).endswith("with the lamps"), \
        volumes.offer(scene)
    glossy = "ShaderNodeBsdfGlossy" if hasattr(bpy.types, "ShaderNodeBsdfGlossy") else "ShaderNodeBsdfAnisotropic"
    group = bpy.data.node_groups.new("shiny", "ShaderNodeTree")
    group.nodes.new(glossy)
    matte.node_tree.nodes.new("ShaderNodeGroup").node_tree = group
    assert volumes.scene_reflects(scene)
    assert volumes.offer(scene) == volumes.REFLECTIONS if traced_alone else "sphere" in volumes.offer(scene), \
        volumes.offer(scene)
    layer = scene.view_layers[0]
    layer.material_override = _material("clay", "ShaderNodeBsdfDiffuse")  # a clay render: nothing reflects
    assert not volumes.scene_reflects(scene)
    layer.material_override = _material("chrome", "ShaderNodeBsdfPrincipled")
    assert volumes.scene_reflects(scene)
    layer.material_override = None
    cube.hide_render = True  # no object left to reflect: the click adds no sphere, and fails on nothing
    assert bpy.ops.probe_lights.eevee_ray_tracing() == {"FINISHED"} and not volumes.sphere_probes(scene)
    cube.hide_render = False
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert not scene.eevee.use_raytracing and not volumes.sphere_probes(scene)
    scene.render.engine = "CYCLES"
