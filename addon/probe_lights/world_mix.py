"""Never light a scene twice: a Light Path mix in the world tree that keeps the world only for the effects the
user keeps from it (camera background, reflections, diffuse), and a restore that takes it out again exactly.

    [original surface] ----------------------- Shader (fac 1)
                                                             Mix Shader --> World Output
    [Background, strength 0] ----------------- Shader (fac 0)
    Light Path: Is Camera / Is Glossy / Is Diffuse Ray -> (Maximum) -> Fac

When the lamps take only the bright sources (Lamps take: The bright sources), the rays that would see nothing
see the residual instead: a Background of the residual image (what the core's split leaves of the probe, packed
in the .blend), looked up along the same directions as the probe at its strength, so that lamps and residual
together are the world's light, once.

Every node it adds carries the custom property "probe_lights"; the mix also carries world_graph.MIX_TAG. Nothing
else in the tree is touched, so removing the tagged nodes and linking the original surface back restores it.
EEVEE lights diffuse and reflections from one world probe, so it cannot keep only the world's reflections. EEVEE
Legacy (3.x) captures that probe as a non-camera, non-glossy ray, so the mix above gives it no world light. EEVEE
Next (4.2+) captures it as a glossy ray (a world kept for glossy rays lit the objects fully: the scene twice;
tests/blender/test_eevee.py). So when the world keeps reflections but not diffuse light, EEVEE gets a World Output of its own
(target EEVEE) that shows the world to the camera only: in EEVEE the lamps then light everything, once.
"""

from dataclasses import dataclass

import bpy
import numpy as np

from .world_graph import MIX_TAG, transpose, uses_nodes

NODE_TAG = "probe_lights"
ENABLED_NODES_TAG = "probe_lights_enabled_nodes"
EEVEE_OUTPUT_TAG = "probe_lights_eevee_output"


@dataclass
class Residual:
    image: object            # the residual as a packed float image
    projection: str          # the Environment Texture's: "EQUIRECTANGULAR" | "MIRROR_BALL"
    lookup: list             # 3x3: world direction -> the image's direction (the probe's chain)
    strength: float          # the probe's Background strength


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
    return Residual(image, projection, transpose(source.world_from_probe), source.strength)


def _residual_background(tree, residual, add, dy):
    """Background <- Environment Texture (the residual) <- Mapping (the probe's turn) <- Texture Coordinate."""
    bg = add("ShaderNodeBackground", -220, dy)
    env = add("ShaderNodeTexEnvironment", -440, dy)
    env.image = residual.image
    env.projection = residual.projection
    tree.links.new(env.outputs["Color"], bg.inputs["Color"])
    identity = all(abs(residual.lookup[i][j] - (i == j)) < 1e-12 for i in range(3) for j in range(3))
    if not identity:
        from mathutils import Matrix
        mapping = add("ShaderNodeMapping", -660, dy)
        mapping.vector_type = "POINT"
        mapping.inputs["Rotation"].default_value = Matrix(residual.lookup).to_euler("XYZ")
        coords = add("ShaderNodeTexCoord", -880, dy)
        tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        tree.links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    # The probe's strength now: a driver on the world's own tree reading it would be a dependency cycle, so a
    # later change of the strength is not followed here as the lamps follow it (docs/blender.md: bake again).
    bg.inputs["Strength"].default_value = residual.strength
    return bg


def _tagged(tree):
    return [n for n in tree.nodes if n.get(NODE_TAG)]


def has_mix(world):
    return world is not None and world.node_tree is not None and any(n.get(MIX_TAG) for n in world.node_tree.nodes)


def _active_output(tree):
    """The World Output Cycles renders (never the EEVEE-only one this module adds)."""
    outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputWorld" and not n.get(EEVEE_OUTPUT_TAG)]
    active = [n for n in outputs if n.is_active_output] or outputs
    return active[0] if active else None


def insert_mix(world, keep_background=True, keep_reflections=True, keep_diffuse=False, residual=None):
    """Routes the world's surface through the mix; replaces an earlier mix of ours. `residual` (residual_world):
    what the rays that do not see the world see, instead of nothing."""
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
    kept = [name for name, keep in (("Is Camera Ray", keep_background), ("Is Glossy Ray", keep_reflections),
                                    ("Is Diffuse Ray", keep_diffuse)) if keep]
    if kept:
        path = add("ShaderNodeLightPath", -660, 0)
        fac = path.outputs[kept[0]]
        for i, name in enumerate(kept[1:]):
            m = add("ShaderNodeMath", -440, -120 * i)
            m.operation = "MAXIMUM"
            tree.links.new(fac, m.inputs[0])
            tree.links.new(path.outputs[name], m.inputs[1])
            fac = m.outputs[0]
        tree.links.new(fac, mix.inputs["Fac"])
    else:
        mix.inputs["Fac"].default_value = 0.0
    tree.links.new(mix.outputs["Shader"], surface)
    if keep_reflections and not keep_diffuse:
        _eevee_output(tree, out, original, keep_background, add, residual)
    for node in added:
        node.parent = frame  # keeps each node where it is
    return mix


def _eevee_output(tree, out, original, keep_background, add, residual=None):
    """A World Output for EEVEE only whose world is seen by the camera and lights nothing, or with a residual
    lights with the residual alone (see the module's doc)."""
    eevee = add("ShaderNodeOutputWorld", 220, -340)
    eevee[EEVEE_OUTPUT_TAG] = 1
    eevee.target = "EEVEE"
    if out.target == "ALL":  # the user's output stays the one Cycles uses; a new output node may have taken
        out.is_active_output = True  # the active flag
    mix = add("ShaderNodeMixShader", 0, -340)
    if residual is not None:
        dark = _residual_background(tree, residual, add, -500)
    else:
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
    if world is None or world.node_tree is None:
        return False
    tree = world.node_tree
    mixes = [n for n in tree.nodes if n.get(MIX_TAG)]
    if not mixes and not _tagged(tree):
        return False
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
