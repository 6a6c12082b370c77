"""Finding the light probe in a world's node tree: rules only, no bpy.

Works on anything shaped like Blender's node API (bl_idname, inputs, outputs, links, node_tree), so it is tested with
plain Python objects as well as in Blender. The result says either where the probe's pixels are and how they are
turned before they light the world, or why the world has to be rendered to a lat-long image instead.

What is followed, from the active World Output's Surface input upstream:
  Background (strength: a constant)  <- Color: Environment Texture (lat-long or mirror ball, an image)
      <- Vector: any chain of Mapping (Point, Texture, Vector, Normal) and Vector Rotate nodes
         <- Texture Coordinate "Generated" (or nothing: the view direction)
through Reroutes, node groups (in and out of them) and the add-on's own Light Path mix. Anything else (Sky Texture,
mixes of backgrounds, colour ramps on the image, a plain colour, ...) is rendered.
"""

from dataclasses import dataclass, field
import math

try:
    from .blender_caps import world_always_uses_nodes
except ImportError:  # imported on its own, as the bpy-free tests do
    from blender_caps import world_always_uses_nodes

MIX_TAG = "probe_lights_mix"  # custom property on the Mix Shader the add-on inserts (see world_mix.py)


@dataclass
class ProbeSource:
    image: object = None              # the Blender image to read, or None when the world must be rendered
    projection: str = "latlong"       # "latlong" | "mirror-ball"
    world_from_probe: list = field(default_factory=lambda: [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    strength: float = 1.0
    render_reason: str = ""           # why the world is rendered instead of read ("" when image is set)
    image_node: object = None
    strength_socket: object = None    # the Background's Strength input (a constant): lamps follow it by drivers
    # When the direction chain is one Mapping node, its Rotation input and whether world_from_probe is the inverse
    # of its Euler rotation (Point/Vector/Normal) or the rotation itself (Texture): lamps follow it by drivers.
    rotation_socket: object = None
    rotation_inverted: bool = True


def euler_xyz_matrix(rx, ry, rz):
    """Blender's Euler XYZ rotation (mathutils, Mapping and Vector Rotate nodes): R = Rz @ Ry @ Rx."""
    cx, sx, cy, sy, cz, sz = math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry), math.cos(rz), math.sin(rz)
    return [
        [cy * cz, sx * sy * cz - cx * sz, cx * sy * cz + sx * sz],
        [cy * sz, sx * sy * sz + cx * cz, cx * sy * sz - sx * cz],
        [-sy, sx * cy, cx * cy],
    ]


def axis_angle_matrix(axis, angle):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    if n == 0:
        return [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    x, y, z = x / n, y / n, z / n
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


class _Render(Exception):
    """The world cannot be read as an image; the message says why (shown to the user)."""


def is_our_mix(node):
    try:
        return bool(node.get(MIX_TAG))
    except (AttributeError, TypeError):
        return False


def _linked_output(socket, groups):
    """The output socket feeding `socket`, through reroutes and node groups; None if unlinked.

    `groups` is the stack of group nodes entered so far (to leave a group through its Group Input)."""
    while True:
        links = [l for l in socket.links if not getattr(l, "is_muted", False)] if socket.is_linked else []
        if not links:
            return None
        out = links[0].from_socket
        node = links[0].from_node
        kind = node.bl_idname
        if kind == "NodeReroute":
            socket = node.inputs[0]
        elif kind == "ShaderNodeGroup":
            if node.node_tree is None:
                raise _Render("a node group without a tree")
            outputs = [n for n in node.node_tree.nodes if n.bl_idname == "NodeGroupOutput"]
            active = [n for n in outputs if getattr(n, "is_active_output", True)] or outputs
            if not active:
                raise _Render("node group '%s' has no Group Output" % node.node_tree.name)
            socket = _input_by_identifier(active[0], out.identifier)
            groups = groups + [node]
        elif kind == "NodeGroupInput":
            if not groups:
                raise _Render("a Group Input outside of a group")
            socket = _input_by_identifier(groups[-1], out.identifier)
            groups = groups[:-1]
        else:
            if getattr(node, "mute", False):
                raise _Render("muted node '%s'" % node.name)
            return out, groups


def _input_by_identifier(node, identifier):
    for s in node.inputs:
        if s.identifier == identifier:
            return s
    raise _Render("node '%s' has no input '%s'" % (node.name, identifier))


def _is_zero(v, tol=1e-9):
    return all(abs(c) <= tol for c in v)


def _vector_chain(socket, groups):
    """The rotation A with lookup direction = A @ world direction, for the Environment Texture's Vector input.

    Walking upstream from the texture, each node found is applied to the direction before the ones already seen,
    so its matrix multiplies on the right."""
    a = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    chain = []  # the nodes that turn the direction, texture first
    while True:
        found = _linked_output(socket, groups)
        if found is None:
            if socket.node.bl_idname == "ShaderNodeTexEnvironment":
                return a, chain  # an unlinked Vector on the texture is the view direction
            raise _Render("an unlinked vector input on '%s'" % socket.node.name)
        out, groups = found
        node = out.node
        chain.append(node)
        kind = node.bl_idname
        if kind == "ShaderNodeTexCoord":
            if out.identifier != "Generated":
                raise _Render("texture coordinates '%s' (only Generated is read directly)" % out.name)
            return a, chain[:-1]
        if kind == "ShaderNodeMapping":
            r = _constant(node.inputs["Rotation"], "Mapping rotation")
            s = _constant(node.inputs["Scale"], "Mapping scale") if "Scale" in node.inputs else (1, 1, 1)
            if max(s) - min(s) > 1e-6 * max(abs(c) for c in s) or min(s) <= 0:
                raise _Render("a non-uniform or negative Mapping scale")
            if node.vector_type in ("POINT", "TEXTURE") and not _is_zero(_constant(node.inputs["Location"], "Mapping location")):
                raise _Render("a Mapping location (it moves directions off the sphere)")
            m = euler_xyz_matrix(*r)
            # Point, Vector, Normal: out = R @ v (scale is uniform, directions are normalized);
            # Texture is the inverse transform: out = R^T @ v.
            a = matmul(a, transpose(m) if node.vector_type == "TEXTURE" else m)
            socket = node.inputs["Vector"]
        elif kind == "ShaderNodeVectorRotate":
            if not _is_zero(_constant(node.inputs["Center"], "Vector Rotate center")):
                raise _Render("a Vector Rotate center off the origin")
            t = node.rotation_type
            if t == "EULER_XYZ":
                m = euler_xyz_matrix(*_constant(node.inputs["Rotation"], "Vector Rotate rotation"))
            else:
                angle = _constant(node.inputs["Angle"], "Vector Rotate angle")
                axis = {"X_AXIS": (1, 0, 0), "Y_AXIS": (0, 1, 0), "Z_AXIS": (0, 0, 1)}.get(t)
                if axis is None:
                    axis = _constant(node.inputs["Axis"], "Vector Rotate axis")
                m = axis_angle_matrix(axis, angle)
            a = matmul(a, transpose(m) if node.invert else m)
            socket = node.inputs["Vector"]
        else:
            raise _Render("the texture's vector comes from a %s node" % kind.replace("ShaderNode", ""))


def _constant(socket, what):
    if socket.is_linked:
        raise _Render("%s is driven by other nodes" % what)
    v = socket.default_value
    try:
        return tuple(float(c) for c in v)
    except TypeError:
        return float(v)


def find_probe(world, blender_version=(4, 5, 0)):
    """Where the world's light comes from: a ProbeSource (image set, or render_reason set). blender_version:
    bpy.app.version of the Blender the world is in (what it renders differs between versions)."""
    try:
        return _find(world, blender_version)
    except _Render as why:
        return ProbeSource(render_reason=str(why))


def uses_nodes(world, blender_version):
    """Whether Blender renders the world through its node tree. From 5.0 on it always does (World.use_nodes is
    deprecated, and measured: Cycles 5.0 renders a world with use_nodes False through its Background node)."""
    if world_always_uses_nodes(blender_version):
        return world.node_tree is not None
    return bool(world.use_nodes) and world.node_tree is not None


def _find(world, blender_version):
    if world is None:
        raise ValueError("the scene has no world")
    if not uses_nodes(world, blender_version):
        raise _Render("the world uses a plain colour, not nodes")
    # The output Cycles renders: an EEVEE-only output (the add-on's own among them, world_mix.py) is not it.
    outputs = [n for n in world.node_tree.nodes
               if n.bl_idname == "ShaderNodeOutputWorld" and getattr(n, "target", "ALL") != "EEVEE"]
    active = [n for n in outputs if n.is_active_output] or outputs
    if not active:
        raise _Render("the world has no World Output")
    found = _linked_output(active[0].inputs["Surface"], [])
    while found is not None and is_our_mix(found[0].node):
        found = _linked_output(found[0].node.inputs[2], found[1])  # the original surface behind our mix
    if found is None:
        raise _Render("nothing is connected to the World Output")
    out, groups = found
    bg = out.node
    if bg.bl_idname != "ShaderNodeBackground":
        raise _Render("the world surface is a %s, not a Background" % bg.bl_idname.replace("ShaderNode", ""))
    strength = _constant(bg.inputs["Strength"], "Background strength")
    colour = _linked_output(bg.inputs["Color"], groups)
    if colour is None:
        raise _Render("the background is a plain colour")
    out, groups = colour
    tex = out.node
    if tex.bl_idname != "ShaderNodeTexEnvironment" or out.identifier != "Color":
        raise _Render("the background colour comes from a %s" % tex.bl_idname.replace("ShaderNode", ""))
    if tex.image is None:
        raise ValueError("the world's Environment Texture '%s' has no image" % tex.name)
    projection = {"EQUIRECTANGULAR": "latlong", "MIRROR_BALL": "mirror-ball"}.get(tex.projection)
    if projection is None:
        raise _Render("environment projection %s" % tex.projection)
    lookup_from_world, chain = _vector_chain(tex.inputs["Vector"], groups)
    source = ProbeSource(image=tex.image, projection=projection, world_from_probe=transpose(lookup_from_world),
                         strength=strength, image_node=tex, strength_socket=bg.inputs["Strength"])
    if len(chain) == 1 and chain[0].bl_idname == "ShaderNodeMapping":
        source.rotation_socket = chain[0].inputs["Rotation"]
        source.rotation_inverted = chain[0].vector_type != "TEXTURE"
    return source


def sequence_number(frame, start, duration, offset, cyclic):
    """The number of the image an image sequence shows at scene frame `frame`, by its Image User's Start Frame,
    Frames (duration), Offset and Cyclic, as Blender counts it (BKE_image_user_frame_get): the first image is 1 at
    the start frame; before it the sequence holds image 0 and after its last frame the last image, unless cyclic;
    the offset is added last. None when the sequence has no frames. Checked against Cycles' renders of the
    sequence by tests/blender/test_animation.py."""
    if duration <= 0:
        return None
    n = frame - start + 1
    if cyclic:
        n %= duration
        if n == 0:
            n = duration
    n = min(max(n, 0), duration)
    return n + offset


def sequence_path(path, number):
    """The file of image `number` of the sequence whose file `path` names one image: the last run of digits in its
    file name (not its folder) replaced by the number, padded to as many digits, a negative number as 0
    (Blender's BLI_path_sequence_decode / encode). None when the file name has no digits."""
    cut = max(path.rfind("/"), path.rfind("\\")) + 1
    folder, name = path[:cut], path[cut:]
    stem, dot, ext = name.rpartition(".") if "." in name else (name, "", "")
    digits = len(stem) - len(stem.rstrip("0123456789"))
    if digits == 0:
        return None
    return folder + stem[:len(stem) - digits] + str(max(number, 0)).zfill(digits) + dot + ext
