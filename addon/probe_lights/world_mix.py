"""Never light a scene twice: the world keeps only the effects the user keeps from it (camera background,
reflections, diffuse), and a restore takes that out again exactly.

    [original surface] ----------------------- Shader (Fac 1)
                                                             Mix Shader --> World Output
    [Background, strength 0 | the residual] -- Shader (Fac 0)
    Fac: Light Path "Is Camera Ray" (or 1 - it, or a constant)

The camera's rays are routed by the mix; the light rays by the world's own Cycles ray visibility (Diffuse and
Volume Scatter off when the lamps take diffuse light, Glossy and Transmission off when they take reflections),
never by "Is Glossy Ray" / "Is Diffuse Ray" in the mix. Why: Cycles samples one closure of a Principled BSDF but
carries the whole BSDF's value on the ray, labelled with that closure, and evaluates the world for light sampling
with no ray type at all; a mix that shows the world to glossy rays only therefore gives a glossy material the
wrong share of it. Measured on 7 probes (bpy 4.5.15, Principled roughness 0.2-1.0, 64 lamps; bench/bench_glossy.py,
docs/results/glossy.md): 0.7-5.2 % from the world's render through the mix, 0.3-2.2 % through the visibility, which
Cycles applies per closure when it samples the world as a light. Transmission goes with reflections: glass
refracts the world, and lamps lighting it through transmission too made a glass sphere 8-12 % too bright (0.4-0.6
% with the world alone lighting it; tests/blender/test_render.py).

When the lamps take only the bright sources (Lamps take: The bright sources), every ray but the camera's sees
the residual (what the core's split leaves of the probe, packed in the .blend, looked up through the probe's own
Vector input at its strength, so that it turns and scales with the probe as the lamps do) and the lamps light every
effect: lamps and residual together are the world's light, once, with nothing routed by effect (0.2-0.7 % from the
world on glossy materials at 64 lamps, same bench).

Every node it adds carries the custom property "probe_lights"; the mix also carries world_graph.MIX_TAG; the
world's ray visibility before the bake is kept in its VISIBILITY_TAG property. Nothing else is touched, so
removing the tagged nodes, linking the original surface back and setting the flags back restores it.
EEVEE lights diffuse and reflections from one world probe and ignores Cycles' ray visibility, so it cannot keep
only the world's reflections: when the world keeps reflections or diffuse light for Cycles, EEVEE gets a World
Output of its own (target EEVEE) that shows the world to the camera only: in EEVEE the lamps then light
everything, once (tests/blender/test_eevee.py). With a residual the mix is already what EEVEE needs.
"""

from dataclasses import dataclass

import bpy
import numpy as np

from .world_graph import MIX_TAG, find_probe, transpose, uses_nodes

NODE_TAG = "probe_lights"
ENABLED_NODES_TAG = "probe_lights_enabled_nodes"
EEVEE_OUTPUT_TAG = "probe_lights_eevee_output"
VISIBILITY_TAG = "probe_lights_visibility"  # the world's Cycles ray visibility before the bake
FOLLOWS_TAG = "probe_lights_follows_strength"  # on the residual's Background: its strength is the probe's
RAYS = ("diffuse", "glossy", "transmission", "scatter")


@dataclass
class Residual:
    image: object            # the residual as a packed float image
    projection: str          # the Environment Texture's: "EQUIRECTANGULAR" | "MIRROR_BALL"
    lookup: list             # 3x3: world direction -> the image's direction (the probe's chain)
    strength: float          # the probe's Background strength
    shares_vector: bool = False  # look the residual up through the probe's own Vector input (it follows it)
    vector_from: object = None   # the socket linked to the probe's Environment Texture's Vector (None: unlinked)
    interpolation: str = "Linear"
    follows_strength: bool = False  # the strength follows the probe's, as the lamps' do (follow_strength)


def residual_world(world, residual, source):
    """The residual (H x W x 3 float32, rows top to bottom, in the probe image's frame) as a packed float image,
    with how the world reads the probe (world_graph.ProbeSource `source`). Replaces an earlier one of ours."""
    name = "Probe Lights residual (%s)" % world.name
    old = bpy.data.images.get(name)
    if old is not None and old.get(NODE_TAG):
        bpy.data.images.remove(old)
    h, w = residual.shape[:2]
    image = bpy.data.images.new(name, w, h, alpha=True, float_buffer=True)
    image[NODE_TAG] = 1
    rgba = np.ones((h, w, 4), np.float32)  # alpha 1: the EXR it is packed as keeps the values exactly
    rgba[..., :3] = residual[::-1]  # Blender stores the bottom row first
    image.pixels.foreach_set(rgba.ravel())
    image.file_format = "OPEN_EXR"
    image.pack()
    projection = "MIRROR_BALL" if source.projection == "mirror-ball" else "EQUIRECTANGULAR"
    out = Residual(image, projection, transpose(source.world_from_probe), source.strength)
    # The residual turns and scales with the probe exactly when the lamps do (light_objects.py: by drivers on the
    # one Mapping node and the Background's strength): it is then looked up through the probe's own Vector input
    # (any later change of the chain is the probe's too) and its strength kept to the probe's (follow_strength).
    node = source.image_node
    if node is not None and node.id_data == world.node_tree:
        vector = node.inputs["Vector"]
        if not vector.is_linked or source.rotation_socket is not None:
            out.shares_vector = True
            out.vector_from = vector.links[0].from_socket if vector.is_linked else None
            out.interpolation = node.interpolation
    out.follows_strength = source.strength_socket is not None and float(source.strength) != 0.0
    return out


def _residual_background(tree, residual, add, dy):
    """Background <- Environment Texture (the residual) <- Mapping (the probe's turn) <- Texture Coordinate."""
    bg = add("ShaderNodeBackground", -220, dy)
    env = add("ShaderNodeTexEnvironment", -440, dy)
    env.image = residual.image
    env.projection = residual.projection
    tree.links.new(env.outputs["Color"], bg.inputs["Color"])
    identity = all(abs(residual.lookup[i][j] - (i == j)) < 1e-12 for i in range(3) for j in range(3))
    if residual.shares_vector:
        env.interpolation = residual.interpolation
        if residual.vector_from is not None:
            tree.links.new(residual.vector_from, env.inputs["Vector"])
    elif not identity:
        from mathutils import Matrix
        mapping = add("ShaderNodeMapping", -660, dy)
        mapping.vector_type = "POINT"
        mapping.inputs["Rotation"].default_value = Matrix(residual.lookup).to_euler("XYZ")
        coords = add("ShaderNodeTexCoord", -880, dy)
        tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        tree.links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    bg.inputs["Strength"].default_value = residual.strength
    if residual.follows_strength:
        bg[FOLLOWS_TAG] = 1
    return bg


def follow_strength(world):
    """Keeps the residual's Background strength to the probe's, as the lamps' drivers keep theirs. Not a driver: one
    on the world's tree reading its own Background is a dependency cycle (bpy 4.5.15 says so); it runs after every
    depsgraph update and before every render (light_objects.py). True when it changed the strength."""
    if world is None or world.node_tree is None:
        return False
    bg = next((n for n in world.node_tree.nodes if n.get(FOLLOWS_TAG) and n.bl_idname == "ShaderNodeBackground"),
              None)
    if bg is None:
        return False
    try:
        source = find_probe(world, bpy.app.version)
    except ValueError:  # no world image now: the panel says so
        return False
    if source.image is None or source.strength_socket is None:
        return False
    strength = source.strength_socket.default_value
    if bg.inputs["Strength"].default_value == strength:
        return False
    bg.inputs["Strength"].default_value = strength
    return True


def _tagged(tree):
    return [n for n in tree.nodes if n.get(NODE_TAG)]


def has_residual(world):
    """Whether the world's light rays see a residual of ours (Lamps take: The bright sources)."""
    return (world is not None and world.node_tree is not None
            and any(n.get(NODE_TAG) and n.bl_idname == "ShaderNodeTexEnvironment" for n in world.node_tree.nodes))


def has_mix(world):
    return world is not None and world.node_tree is not None and any(n.get(MIX_TAG) for n in world.node_tree.nodes)


def _active_output(tree):
    """The World Output Cycles renders (never the EEVEE-only one this module adds)."""
    outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputWorld" and not n.get(EEVEE_OUTPUT_TAG)]
    active = [n for n in outputs if n.is_active_output] or outputs
    return active[0] if active else None


def insert_mix(world, keep_background=True, keep_reflections=True, keep_diffuse=False, residual=None):
    """Routes the world's surface through the mix; replaces an earlier mix of ours. `residual` (residual_world):
    what every ray but the camera's sees (keep_reflections and keep_diffuse do not apply: the lamps of the sources
    light every effect)."""
    remove_mix(world)
    if not uses_nodes(world, bpy.app.version):
        # A plain-colour world (before Blender 5.0): give it the node tree Blender would, remembering to switch it
        # back on restore.
        colour = tuple(world.color) + (1.0,)
        world.use_nodes = True
        world[ENABLED_NODES_TAG] = 1
        bg = next((n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeBackground"), None)
        if bg is not None:
            bg.inputs["Color"].default_value = colour
    tree = world.node_tree
    out = _active_output(tree)
    if out is None:
        out = tree.nodes.new("ShaderNodeOutputWorld")
        out[NODE_TAG] = 1
    surface = out.inputs["Surface"]
    original = surface.links[0].from_socket if surface.is_linked else None

    # The added nodes go in a labelled frame below the user's nodes, ending under the output they feed.
    user = [n for n in tree.nodes if not n.get(NODE_TAG)]
    top = min((n.location.y - max(n.dimensions.y, 160.0) for n in user), default=out.location.y) - 80.0
    frame = tree.nodes.new("NodeFrame")
    frame[NODE_TAG] = 1
    frame.label = "Probe Lights: the world's share after the bake (Restore world takes it out)"
    frame.shrink = True
    frame.location = (0.0, 0.0)
    added = []

    def add(kind, dx, dy):
        node = tree.nodes.new(kind)
        node[NODE_TAG] = 1
        node.location = (out.location.x + dx, top + dy)
        node.label = "Probe Lights"
        added.append(node)
        return node

    mix = add("ShaderNodeMixShader", 0, 0)
    mix[MIX_TAG] = 1
    if residual is not None:
        dark = _residual_background(tree, residual, add, -160)
    else:
        dark = add("ShaderNodeBackground", -220, -160)
        dark.inputs["Strength"].default_value = 0.0
        dark.inputs["Color"].default_value = (0, 0, 0, 1)
    tree.links.new(dark.outputs["Background"], mix.inputs[1])
    if original is not None:
        tree.links.new(original, mix.inputs[2])
    # Which rays see the original (mix input 2, weight Fac): the camera's, and with all of the light in the lamps
    # the light rays of the effects the world keeps, which Cycles routes by the world's own ray visibility below.
    keeps_light = residual is None and (keep_reflections or keep_diffuse)
    if keeps_light and keep_background:
        mix.inputs["Fac"].default_value = 1.0
    elif keeps_light or keep_background:
        path = add("ShaderNodeLightPath", -660, 0)
        fac = path.outputs["Is Camera Ray"]
        if not keep_background:  # every ray but the camera's
            m = add("ShaderNodeMath", -440, 0)
            m.operation = "SUBTRACT"
            m.inputs[0].default_value = 1.0
            tree.links.new(fac, m.inputs[1])
            fac = m.outputs[0]
        tree.links.new(fac, mix.inputs["Fac"])
    else:
        mix.inputs["Fac"].default_value = 0.0
    tree.links.new(mix.outputs["Shader"], surface)
    if keeps_light:
        _route_by_visibility(world, diffuse=keep_diffuse, glossy=keep_reflections)
        if not (keep_reflections and keep_diffuse):
            _eevee_output(tree, out, original, keep_background, add)
    for node in added:
        node.parent = frame  # keeps each node where it is
    return mix


def _route_by_visibility(world, diffuse, glossy):
    """Lets the world light only the effects it keeps, by its Cycles ray visibility (Diffuse and Volume Scatter;
    Glossy and Transmission, which go together: glass refracts the world as it reflects it), remembering the user's
    flags for remove_mix. A flag the user had off stays off."""
    vis = world.cycles_visibility
    if VISIBILITY_TAG not in world:
        world[VISIBILITY_TAG] = {ray: int(getattr(vis, ray)) for ray in RAYS}
    for ray, keep in (("diffuse", diffuse), ("scatter", diffuse), ("glossy", glossy), ("transmission", glossy)):
        setattr(vis, ray, bool(world[VISIBILITY_TAG][ray]) and keep)


def _restore_visibility(world):
    saved = world.get(VISIBILITY_TAG)
    if saved is None:
        return False
    for ray in RAYS:
        setattr(world.cycles_visibility, ray, bool(saved[ray]))
    del world[VISIBILITY_TAG]
    return True


def _eevee_output(tree, out, original, keep_background, add):
    """A World Output for EEVEE only whose world is seen by the camera and lights nothing (see the module's
    doc)."""
    eevee = add("ShaderNodeOutputWorld", 220, -340)
    eevee[EEVEE_OUTPUT_TAG] = 1
    eevee.target = "EEVEE"
    if out.target == "ALL":  # the user's output stays the one Cycles uses; a new output node may have taken
        out.is_active_output = True  # the active flag
    mix = add("ShaderNodeMixShader", 0, -340)
    dark = add("ShaderNodeBackground", -220, -500)
    dark.inputs["Strength"].default_value = 0.0
    tree.links.new(dark.outputs["Background"], mix.inputs[1])
    if original is not None:
        tree.links.new(original, mix.inputs[2])
    if keep_background:
        path = add("ShaderNodeLightPath", -660, -340)
        tree.links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    else:
        mix.inputs["Fac"].default_value = 0.0
    tree.links.new(mix.outputs["Shader"], eevee.inputs["Surface"])


def remove_mix(world):
    """Takes the add-on's nodes out and links the original surface back. True if there was anything to remove."""
    if world is None:
        return False
    restored = _restore_visibility(world)
    if world.node_tree is None:
        return restored
    tree = world.node_tree
    mixes = [n for n in tree.nodes if n.get(MIX_TAG)]
    if not mixes and not _tagged(tree):
        return restored
    out = _active_output(tree)
    original = None
    for mix in mixes:
        shader = mix.inputs[2]
        if shader.is_linked:
            original = shader.links[0].from_socket
    images = {n.image for n in _tagged(tree) if n.bl_idname == "ShaderNodeTexEnvironment" and n.image is not None}
    for node in _tagged(tree):
        tree.nodes.remove(node)
    for image in images:  # the residual images of ours nothing else uses
        if image.get(NODE_TAG) and image.users == 0:
            bpy.data.images.remove(image)
    if out is not None:
        if out.get(NODE_TAG + "_moved"):  # baked by version 0.1, which moved the output to make room
            out.location.x -= 220
            del out[NODE_TAG + "_moved"]
        if original is not None:
            tree.links.new(original, out.inputs["Surface"])
    if world.get(ENABLED_NODES_TAG):
        del world[ENABLED_NODES_TAG]
        world.use_nodes = False
    return True
