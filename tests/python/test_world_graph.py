"""The add-on's world-reading rules on fake node trees (no Blender needed), and its unit conversions."""

import math

import numpy as np
import pytest

import blender_caps
import conversion
import world_graph as wg


class Socket:
    def __init__(self, node, name, default=None, identifier=None):
        self.node, self.name, self.identifier, self.default_value = node, name, identifier or name, default
        self.links = []

    @property
    def is_linked(self):
        return bool(self.links)


class Sockets(list):
    def __getitem__(self, key):
        if isinstance(key, str):
            for s in self:
                if s.name == key:
                    return s
            raise KeyError(key)
        return list.__getitem__(self, key)

    def __contains__(self, key):
        return any(s.name == key for s in self) if isinstance(key, str) else list.__contains__(self, key)


class Link:
    def __init__(self, from_socket, to_socket):
        self.from_socket, self.to_socket = from_socket, to_socket
        self.from_node, self.to_node = from_socket.node, to_socket.node


class Node(dict):
    def __init__(self, bl_idname, inputs=(), outputs=(), **attrs):
        super().__init__()
        self.bl_idname, self.name, self.mute = bl_idname, bl_idname, False
        self.inputs = Sockets(Socket(self, *i) if isinstance(i, tuple) else Socket(self, i) for i in inputs)
        self.outputs = Sockets(Socket(self, o) for o in outputs)
        self.__dict__.update(attrs)


class Tree:
    def __init__(self, *nodes):
        self.nodes, self.name = list(nodes), "tree"

    def add(self, node):
        self.nodes.append(node)
        return node


def link(out, inp):
    inp.links.append(Link(out, inp))


class World:
    def __init__(self, tree, use_nodes=True):
        self.node_tree, self.use_nodes = tree, use_nodes


def output_and_background(strength=1.0):
    out = Node("ShaderNodeOutputWorld", ["Surface"], is_active_output=True)
    bg = Node("ShaderNodeBackground", [("Color", (1, 1, 1, 1)), ("Strength", strength)], ["Background"])
    link(bg.outputs["Background"], out.inputs["Surface"])
    return out, bg


def env_node(image="img", projection="EQUIRECTANGULAR"):
    return Node("ShaderNodeTexEnvironment", ["Vector"], ["Color"], image=image, projection=projection)


def mapping(rotation, vector_type="POINT", scale=(1, 1, 1), location=(0, 0, 0)):
    return Node("ShaderNodeMapping", ["Vector", ("Location", location), ("Rotation", rotation), ("Scale", scale)],
                ["Vector"], vector_type=vector_type)


def simple_world(strength=2.0, vector_chain=()):
    out, bg = output_and_background(strength)
    env = env_node()
    link(env.outputs["Color"], bg.inputs["Color"])
    tree = Tree(out, bg, env)
    target = env.inputs["Vector"]
    for node in vector_chain:
        tree.add(node)
        link(node.outputs["Vector"], target)
        target = node.inputs["Vector"]
    if vector_chain:
        coords = tree.add(Node("ShaderNodeTexCoord", [], ["Generated", "Object"]))
        link(coords.outputs["Generated"], target)
    return World(tree), out, bg, env


def test_environment_texture_is_read_with_its_strength():
    world, *_ = simple_world(strength=2.0)
    s = wg.find_probe(world)
    assert s.image == "img" and s.projection == "latlong" and s.strength == 2.0 and not s.render_reason
    assert np.allclose(s.world_from_probe, np.eye(3))


def test_euler_xyz_is_blenders():
    # 90 degrees about Z takes +X to +Y; XYZ order means R = Rz Ry Rx.
    assert np.allclose(np.array(wg.euler_xyz_matrix(0, 0, math.pi / 2)) @ [1, 0, 0], [0, 1, 0])
    rx, ry, rz = 0.3, -0.7, 1.1
    c, s = math.cos, math.sin
    Rx = np.array([[1, 0, 0], [0, c(rx), -s(rx)], [0, s(rx), c(rx)]])
    Ry = np.array([[c(ry), 0, s(ry)], [0, 1, 0], [-s(ry), 0, c(ry)]])
    Rz = np.array([[c(rz), -s(rz), 0], [s(rz), c(rz), 0], [0, 0, 1]])
    assert np.allclose(wg.euler_xyz_matrix(rx, ry, rz), Rz @ Ry @ Rx)


@pytest.mark.parametrize("vector_type, inverse", [("POINT", False), ("VECTOR", False), ("NORMAL", False),
                                                   ("TEXTURE", True)])
def test_mapping_rotation(vector_type, inverse):
    rot = (0.2, 0.5, -1.0)
    world, *_ = simple_world(vector_chain=[mapping(rot, vector_type)])
    r = np.array(wg.euler_xyz_matrix(*rot))
    expected = r if inverse else r.T  # lookup = R d  =>  world direction = R^T (probe direction)
    assert np.allclose(wg.find_probe(world).world_from_probe, expected)


def test_vector_rotate_chain_composes():
    rot_node = Node("ShaderNodeVectorRotate", ["Vector", ("Center", (0, 0, 0)), ("Axis", (0, 0, 1)), ("Angle", 0.4),
                                                ("Rotation", (0, 0, 0))], ["Vector"], rotation_type="Z_AXIS",
                    invert=False)
    m = mapping((0.1, 0, 0))
    world, *_ = simple_world(vector_chain=[rot_node, m])  # env <- rotate <- mapping <- coords
    # The mapping is applied to the view direction first, then the rotation: lookup = Rrotate @ Rmapping @ d.
    lookup = np.array(wg.axis_angle_matrix((0, 0, 1), 0.4)) @ np.array(wg.euler_xyz_matrix(0.1, 0, 0))
    assert np.allclose(wg.find_probe(world).world_from_probe, lookup.T)


@pytest.mark.parametrize("node, reason", [
    (mapping((0, 0, 0), scale=(1, 2, 1)), "non-uniform"),
    (mapping((0, 0, 0), location=(0, 0, 1)), "location"),
])
def test_mappings_that_are_not_rotations_are_rendered(node, reason):
    world, *_ = simple_world(vector_chain=[node])
    s = wg.find_probe(world)
    assert s.image is None and reason in s.render_reason


def test_other_worlds_are_rendered_with_a_reason():
    out, bg = output_and_background()
    sky = Node("ShaderNodeTexSky", [], ["Color"])
    link(sky.outputs["Color"], bg.inputs["Color"])
    assert "TexSky" in wg.find_probe(World(Tree(out, bg, sky))).render_reason
    out, bg = output_and_background()
    assert "plain colour" in wg.find_probe(World(Tree(out, bg))).render_reason
    assert "plain colour" in wg.find_probe(World(None, use_nodes=False)).render_reason
    out = Node("ShaderNodeOutputWorld", ["Surface"], is_active_output=True)
    assert "nothing is connected" in wg.find_probe(World(Tree(out))).render_reason


def test_missing_image_and_world_are_errors():
    world, out, bg, env = simple_world()
    env.image = None
    with pytest.raises(ValueError, match="has no image"):
        wg.find_probe(world)
    with pytest.raises(ValueError, match="no world"):
        wg.find_probe(None)


def test_our_own_mix_is_looked_through():
    world, out, bg, env = simple_world()
    mix = Node("ShaderNodeMixShader", ["Fac", ("Shader", None, "Shader"), ("Shader", None, "Shader_001")], ["Shader"])
    mix[wg.MIX_TAG] = 1
    out.inputs["Surface"].links.clear()
    link(bg.outputs["Background"], mix.inputs[2])
    link(mix.outputs["Shader"], out.inputs["Surface"])
    world.node_tree.add(mix)
    assert wg.find_probe(world).image == "img"


def test_groups_and_reroutes_are_followed():
    out, bg = output_and_background()
    group_tree = Tree()
    env = group_tree.add(env_node())
    group_out = group_tree.add(Node("NodeGroupOutput", ["Color"], is_active_output=True))
    link(env.outputs["Color"], group_out.inputs["Color"])
    group = Node("ShaderNodeGroup", [], ["Color"], node_tree=group_tree)
    reroute = Node("NodeReroute", ["Input"], ["Output"])
    link(group.outputs["Color"], reroute.inputs[0])
    link(reroute.outputs["Output"], bg.inputs["Color"])
    assert wg.find_probe(World(Tree(out, bg, group, reroute))).image == "img"


def test_sun_parameters_point_the_lamp_and_keep_its_irradiance():
    d = np.array([0.3, -0.4, 0.866])
    d /= np.linalg.norm(d)
    p = conversion.sun_parameters(d, (2.0, 1.0, 0.5), angle=0.2, blender_version=(3, 4, 1))
    rot = p["rotation"]
    assert np.allclose(rot.T @ rot, np.eye(3)) and np.isclose(np.linalg.det(rot), 1)
    assert np.allclose(rot[:, 2], d)  # local +Z towards the light: a sun shines along its -Z
    assert p["color"] == (1.0, 0.5, 0.25) and p["angle"] == pytest.approx(0.2)
    assert p["energy"] * conversion.sun_normal_irradiance(p["angle"], (3, 4, 1)) == pytest.approx(2.0)
    assert p["energy"] > 2.0  # Blender 3.4's wide suns give less than their strength
    assert conversion.sun_parameters(d, (2, 1, 0.5), 0.2, (4, 5, 0))["energy"] == pytest.approx(2.0)  # 4.0+: S
    assert conversion.sun_parameters(d, (2, 1, 0.5), 0.0, (5, 2, 3))["angle"] == 0.0
    assert conversion.sun_parameters(d, (2, 1, 0.5), 4.0, (5, 2, 3))["angle"] == pytest.approx(math.pi)
    assert conversion.sun_parameters(d, (2, 1, 0.5), 4.0, (3, 4, 1))["angle"] == pytest.approx(math.radians(178))
    assert blender_caps.sun_profile((3, 4, 1)) == "disc" and blender_caps.sun_profile((4, 5, 0)) == "cone"
    # Cones kept above the horizon for EEVEE Next (4.2+) alone: EEVEE Legacy (3.x) and Cycles keep them free.
    assert blender_caps.sun_cones("BLENDER_EEVEE_NEXT", (4, 5, 0)) == "above-horizon"
    assert blender_caps.sun_cones("BLENDER_EEVEE", (5, 3, 0)) == "above-horizon"
    assert blender_caps.sun_cones("BLENDER_EEVEE", (3, 4, 1)) == "free"
    assert blender_caps.sun_cones("CYCLES", (5, 3, 0)) == "free"
    assert blender_caps.preset("BLENDER_EEVEE", (5, 3, 0)) == "blender-eevee"
    assert blender_caps.preset("BLENDER_EEVEE", (3, 4, 1)) == blender_caps.preset("CYCLES", (5, 3, 0)) == "blender"
    # EEVEE's bounce closest to Cycles: ray tracing alone up to 5.1 (5.1 unmeasured: 5.0's), then with a volume
    assert [blender_caps.eevee_bounce(v) for v in ((4, 2, 23), (5, 0, 1), (5, 1, 0), (5, 2, 3), (5, 3, 0))] == [
        "ray tracing"] * 3 + ["volume and ray tracing"] * 2
    straight_up = conversion.rotation_to_direction((0, 0, 1))
    assert np.allclose(straight_up[:, 2], (0, 0, 1))


def test_point_power_gives_the_irradiance_at_the_origin():
    p = conversion.point_parameters((0, 0, 2), (3.0, 3.0, 3.0), distance=5.0)
    assert np.allclose(p["location"], (0, 0, 5))
    assert p["energy"] / (4 * math.pi * 25) == pytest.approx(3.0)


def test_srgb_to_linear():
    assert np.allclose(conversion.srgb_to_linear([0.0, 0.04045, 0.5, 1.0]), [0.0, 0.04045 / 12.92, 0.2140, 1.0],
                       atol=1e-4)



def test_blender_5_renders_every_world_through_its_nodes():
    """World.use_nodes is deprecated in 5.0 and ignored (measured: Cycles 5.0 renders the Background node of a world
    whose use_nodes is False), so from 5.0 on the tree is read whatever the flag says."""
    out, bg = output_and_background()
    world = World(Tree(out, bg), use_nodes=False)
    assert "plain colour, not nodes" in wg.find_probe(world, (4, 5, 0)).render_reason
    assert wg.find_probe(world, (5, 0, 0)).render_reason == "the background is a plain colour"


def test_render_cost_advice_follows_the_running_version():
    """With today's bakes 32 suns render as close as any count in every version on all three probes measured (3.4:
    noise past it; 4.5+: time without gain); the probe whose own sweet spot is the largest decides, and the note
    names the running version's cost: noise or time."""
    import render_cost
    for version in ((3, 4, 1), (4, 5, 15), (5, 0, 1), (5, 2, 3), (5, 3, 0)):
        assert render_cost.sweet_spot(version) == 32
        assert render_cost.count_note(32, version) == ""
    # noon_grass alone would say 16 in 4.5 (0.26 % against the least 0.25 %): forest's 32 decides.
    assert render_cost._probe_sweet_spot(render_cost.MEASURED["cycles"][(4, 5, 15)]["noon_grass"][1]) == 16
    assert render_cost.measured_version((4, 2, 0)) == (4, 5, 15) and render_cost.measured_version((5, 1, 0)) == (5, 0, 1)
    assert render_cost.measured_version((3, 6, 0)) == (3, 4, 1) and render_cost.measured_version((5, 4, 0)) == (5, 3, 0)
    old, new = render_cost.count_note(128, (3, 4, 1)), render_cost.count_note(256, (4, 5, 15))
    # Advice, not figures (those are in render_cost.MEASURED and docs/results/renders.md): noise without a light tree,
    # time with one.
    assert old == "More than 32 suns: noisier renders, no closer in Cycles 3.4", old
    assert new == "More than 32 suns: slower renders, no closer in Cycles 4.5", new


def test_the_default_count_follows_the_engine_measured():
    """Count by Engine: the running engine's sweet spot in the measurements standing for the running Blender (Cycles
    or EEVEE Next, each measured apart); 64 where nothing stands for the engine or the light kind."""
    import render_cost
    for version in ((3, 4, 1), (4, 2, 0), (4, 5, 15), (5, 3, 0)):
        count, why = render_cost.default_count("CYCLES", version)
        assert count == render_cost.sweet_spot(version, "cycles") == 32, (version, count)
        assert why == "more render no closer in Cycles %d.%d" % render_cost.measured_version(version)[:2], why
    assert render_cost.default_count("CYCLES", (4, 5, 15), measured_kind=False) == (
        64, "this light type's renders not measured")
    for engine, version in (("BLENDER_EEVEE", (3, 4, 1)), ("BLENDER_WORKBENCH", (4, 5, 15))):
        assert render_cost.engine_of(engine, version) is None
        assert render_cost.default_count(engine, version) == (64, "renders in this engine not measured")
    for engine, version in (("BLENDER_EEVEE_NEXT", (4, 2, 0)), ("BLENDER_EEVEE_NEXT", (4, 5, 15)),
                            ("BLENDER_EEVEE", (5, 0, 1)), ("BLENDER_EEVEE", (5, 3, 0))):
        assert render_cost.engine_of(engine, version) == "eevee"
        count, why = render_cost.default_count(engine, version)
        assert count == render_cost.sweet_spot(version, "eevee"), (version, count)
        assert why == "more render no closer in EEVEE %d.%d" % render_cost.measured_version(version, "eevee")[:2], why
        best = render_cost.sweet_spot(version, "eevee")
        assert render_cost.count_note(best, version, "eevee") == ""
        assert render_cost.count_note(2 * best, version, "eevee").startswith("More than %d suns: slower renders, no "
                                                                              "closer in EEVEE" % best)


def test_a_sweet_spot_weighs_blocks_and_flip_alike():
    """A count is as close as the closest within 0.1 points by blocks and 0.002 by HDR-FLIP; where none is by both,
    the one whose farther measure is nearest its best (in those units) is."""
    import render_cost
    both = {4: (1.0, 2.0, 0.030), 8: (1.0, 1.05, 0.0215), 16: (1.0, 1.0, 0.020), 32: (1.0, 1.0, 0.020)}
    assert render_cost._probe_sweet_spot(both) == 8
    torn = {4: (1.0, 2.0, 0.030), 8: (1.0, 1.0, 0.050), 16: (1.0, 1.5, 0.020)}  # excess 10, 15, 5
    assert render_cost._probe_sweet_spot(torn) == 16
    assert render_cost._probe_sweet_spot({4: (1.0, 2.0, None), 8: (1.0, 1.95, None)}) == 4  # blocks alone
    # EEVEE 5.3 on noon_grass: 8 suns closest by blocks (1.85 %), 4 by FLIP (0.0236); 8's FLIP is 0.0022 off.
    assert render_cost._probe_sweet_spot(render_cost.MEASURED["eevee"][(5, 3, 0)]["noon_grass"][1]) == 8


def test_image_sequence_frames_are_counted_as_blender_counts_them():
    # Start frame 5, 10 images, offset 2: image 1 (+2) at frame 5; before it image 0, after its end the last one.
    assert [wg.sequence_number(f, 5, 10, 2, False) for f in (1, 4, 5, 6, 14, 15, 16)] == [2, 2, 3, 4, 12, 12, 12]
    # Cyclic: the images repeat before and after.
    assert [wg.sequence_number(f, 5, 10, 2, True) for f in (1, 4, 5, 6, 14, 15, 16, 30)] == [9, 12, 3, 4, 12, 3, 4, 8]
    assert wg.sequence_number(3, 1, 0, 0, False) is None


def test_image_sequence_files_are_named_as_blender_names_them():
    assert wg.sequence_path("/a/b2/sky_0001.exr", 12) == "/a/b2/sky_0012.exr"  # the folder's digits stay
    assert wg.sequence_path("C:\\x7\\s12.hdr", 3) == "C:\\x7\\s03.hdr"
    assert wg.sequence_path("/a/sky_9.exr", 123) == "/a/sky_123.exr"  # more digits than the padding
    assert wg.sequence_path("/a/sky.0001.exr", -2) == "/a/sky.0000.exr"
    assert wg.sequence_path("/a/sky.exr", 3) is None


def test_the_tradeoff_shows_the_measured_render_time_per_count():
    """The Tradeoff's render column: a count's Cycles render time over the world-lit render's, the mean of the
    probes measured in the version standing for the running one, straight between measured counts, none outside."""
    import render_cost
    measured = render_cost.MEASURED["cycles"][(4, 5, 15)]
    at_64 = sum(suns[64][0] / world for world, suns in measured.values()) / len(measured)
    assert abs(render_cost.render_factor(64, (4, 5, 15)) - at_64) < 1e-12
    assert abs(render_cost.render_factor(64, (4, 2, 0)) - at_64) < 1e-12  # 4.2 takes 4.5's measurements
    at_32 = render_cost.render_factor(32, (4, 5, 15))
    assert abs(render_cost.render_factor(48, (4, 5, 15)) - (at_32 + at_64) / 2) < 1e-12
    assert render_cost.render_factor(2, (4, 5, 15)) is None and render_cost.render_factor(999, (4, 5, 15)) is None
    for version in ((4, 5, 15), (5, 0, 1), (5, 2, 3), (5, 3, 0)):  # with a light tree every sun adds time
        factors = [render_cost.render_factor(n, version) for n in (16, 32, 64, 128, 256)]
        assert factors == sorted(factors) and factors[-1] > 4, (version, factors)
