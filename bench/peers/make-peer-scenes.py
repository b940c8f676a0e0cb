#!/usr/bin/env python3
"""Writes the peer benchmark's generated scenes (bench/peers, docs/benchmarks.md):

- bench/peers/scenes/robots_<N>/scene.xml: N copies of bench/peers/scenes/diffbot.xml on a grid;
- bench/peers/mjcf/robots_<N>.xml: the same robots in MuJoCo's MJCF;
- bench/peers/mjcf/pile.xml: scenes/pile/things.xml in MJCF (one body a line: the ODE side of
  the benchmark reads the bodies from this file too).

The numbers of the robot mirror diffbot.xml and bench/peers/peer_model.hpp (the ODE side); the
benchmark compares the engines' outcomes, so a copy that drifted shows. Run from the
repository root with /usr/bin/python3; the files it writes are committed.

`--out DIR --robots N...` writes only robots_N, under DIR/scenes (with a copy of diffbot.xml)
and DIR/mjcf: the build does this for the large counts (LARGE_ROBOT_COUNTS), whose files it
would not pay to commit (1.4 MB for 1024 robots)."""
import argparse
import math
import os
import shutil
import xml.etree.ElementTree as ET

ROBOT_COUNTS = (1, 4, 16, 64)  # committed
LARGE_ROBOT_COUNTS = (256, 1024)  # written into the build folder (bench/peers/CMakeLists.txt)
SPACING_M = 1.5  # between robots of the grid: far enough never to touch
# SimTwo's invisible walls stand at x, y = ±12 m unless a scene moves them (docs/format.md): a
# robot placed beyond them is thrown back by a metres-deep contact. A grid that reaches within
# one spacing of them moves them out, two spacings past its far corner.
SIMTWO_WALLS_M = 12.0

# diffbot.xml, in the robot frame (the robot's pos is its origin on the floor).
BRICK = dict(mass=0.31, size=(0.112, 0.072, 0.040), pos=(-0.03, 0.0, 0.07))
MOTOR_HOUSINGS = [dict(mass=0.08, size=(0.100, 0.035, 0.040), pos=(-0.02, s * 0.0175, 0.03))
                  for s in (-1, 1)]
CASTER = dict(radius=0.014, pos=(-0.09, 0.0, 0.014))
WHEEL = dict(mass=0.02, radius=0.028, width=0.026, half_track=0.06)
MOTOR = dict(ri=7.6, ki=0.4908, imax=2.0, bv=1.92e-3, fc=3.558e-4, rotor_J=1e-5)
# Contacts: S2Sim rings every contact at 0.3 rad per 1 ms step, critically damped
# (docs/models/contact.md); MuJoCo's time constant for the same is 1/300 s.
CONTACT_SOLREF = "0.0033 1"
PILE_FRICTION = 0.95  # S2Sim's default when neither surface sets mu


def grid_position(index, count):
    cols = math.ceil(math.sqrt(count))
    return ((index % cols) * SPACING_M, (index // cols) * SPACING_M)


def fmt(*values):
    return " ".join(f"{v:.10g}" for v in values)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def s2sim_robots_scene(count):
    lines = ["<?xml version='1.0' ?>",
             f"<!-- Made by bench/peers/make-peer-scenes.py; do not edit. {count} differential",
             "     robots (../diffbot.xml) on a grid, driven at fixed voltages by the benchmark. -->",
             "<scene>", "  <s2sim>", "    <physics step_ms='1' substeps='1'/>"]
    cols = math.ceil(math.sqrt(count))
    extent_m = (cols - 1) * SPACING_M
    if extent_m + SPACING_M > SIMTWO_WALLS_M:
        lines.append(f"    <walls active='1' distance='{extent_m + 2 * SPACING_M:g}'/>")
    lines.append("  </s2sim>")
    for i in range(count):
        x, y = grid_position(i, count)
        lines += ["  <robot>", f"    <ID name='r{i}'/>", f"    <pos x='{x:g}' y='{y:g}' z='0'/>",
                  "    <body file='../diffbot.xml'/>", "  </robot>"]
    lines.append("</scene>")
    return "\n".join(lines) + "\n"


def mjcf_header(model_name, comment, contacts=100, rows=500, stack=250000):
    return [f'<mujoco model="{model_name}">',
            f"  <!-- Made by bench/peers/make-peer-scenes.py; do not edit. {comment} -->",
            '  <compiler angle="radian" inertiafromgeom="true"/>',
            # The Newton solver stops at tolerance 1e-8 by default, which let the robots' wheels
            # blow up within 50 ms on robots_4 and robots_16 (robots_1 held): 1e-10 holds all.
            '  <option timestep="0.001" gravity="0 0 -9.81" tolerance="1e-10"/>',
            # MuJoCo 2.2 preallocates 100 contacts and 500 constraint rows unless told; its
            # arena grows with their product with the model's size (2 GB and 12 s to load the
            # pile at 1500 and 6000), so each scene asks for what it needs.
            f'  <size nconmax="{contacts}" njmax="{rows}" nstack="{stack}"/>',
            "  <default>",
            f'    <geom solref="{CONTACT_SOLREF}" friction="{PILE_FRICTION} 0.005 0.0001"/>',
            "  </default>",
            "  <worldbody>",
            # Friction combines by the larger in MuJoCo: a floor of 0 leaves each body's own.
            '    <geom name="floor" type="plane" size="0 0 1" friction="0 0 0"/>']


def mjcf_motor(joint, gain, torque_limit):
    """The DC motor at voltage ctrl, as a torque source Ks/Ri·ctrl within Ks·imax; its back-EMF
    Ks²/Ri is the joint's damping, which MuJoCo's Euler integrates implicitly (as S2Sim does
    its axis drives): explicit, it would be unstable on a light wheel or hand at 1 ms."""
    return (f'    <general name="{joint}" joint="{joint}" gainprm="{gain:.10g}" forcelimited="true"'
            f' forcerange="{fmt(-torque_limit, torque_limit)}"/>')


def mjcf_robots(count):
    m = MOTOR
    gain = m["ki"] / m["ri"]
    damping = m["ki"] * m["ki"] / m["ri"] + m["bv"]
    torque_limit = m["ki"] * m["imax"]
    lines = mjcf_header(f"robots_{count}", f"{count} differential robots, bench/peers.",
                        contacts=10 * count + 20, rows=50 * count + 100, stack=500 * (50 * count + 100))
    actuators = []
    for i in range(count):
        x, y = grid_position(i, count)
        lines += [f'    <body name="r{i}" pos="{fmt(x, y, 0)}">', "      <freejoint/>",
                  f'      <geom name="r{i}_brick" type="box" size="{fmt(*(s / 2 for s in BRICK["size"]))}"'
                  f' pos="{fmt(*BRICK["pos"])}" mass="{BRICK["mass"]:g}"/>']
        for h in MOTOR_HOUSINGS:
            lines.append(f'      <geom type="box" size="{fmt(*(s / 2 for s in h["size"]))}"'
                         f' pos="{fmt(*h["pos"])}" mass="{h["mass"]:g}"/>')
        lines.append(f'      <geom type="sphere" size="{CASTER["radius"]:g}" pos="{fmt(*CASTER["pos"])}"'
                     ' mass="0" friction="0 0 0"/>')
        for side, sign, axis in (("right", -1, 1), ("left", 1, -1)):
            name = f"r{i}_{side}"
            lines += [f'      <body name="{name}" pos="{fmt(0, sign * WHEEL["half_track"], WHEEL["radius"])}">',
                      f'        <joint name="{name}" type="hinge" axis="0 {axis} 0" damping="{damping:.10g}"'
                      f' frictionloss="{m["fc"]:g}" armature="{m["rotor_J"]:g}"/>',
                      f'        <geom type="cylinder" size="{fmt(WHEEL["radius"], WHEEL["width"] / 2)}"'
                      f' zaxis="0 1 0" mass="{WHEEL["mass"]:g}" friction="1 0.005 0.0001"/>',
                      "      </body>"]
            actuators.append(mjcf_motor(name, gain, torque_limit))
        lines.append("    </body>")
    lines += ["  </worldbody>", "  <actuator>"] + actuators + ["  </actuator>", "</mujoco>"]
    return "\n".join(lines) + "\n"


def rot_deg_quaternion(x_deg, y_deg, z_deg):
    """SimTwo's rot_deg: R = Rz(z) Ry(y) Rx(x) (kernel/src/scene/rotation.cpp), as w x y z."""
    hx, hy, hz = (math.radians(a) / 2 for a in (x_deg, y_deg, z_deg))
    qx = (math.cos(hx), math.sin(hx), 0.0, 0.0)
    qy = (math.cos(hy), 0.0, math.sin(hy), 0.0)
    qz = (math.cos(hz), 0.0, 0.0, math.sin(hz))

    def mul(a, b):
        aw, ax, ay, az = a
        bw, bx, by, bz = b
        return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)
    return mul(mul(qz, qy), qx)


def xyz(element, default=0.0):
    if element is None:
        return (default, default, default)
    return tuple(float(element.get(k, default)) for k in ("x", "y", "z"))


def mjcf_pile(things_path):
    lines = mjcf_header("pile", "scenes/pile/things.xml: 100 boxes, 50 spheres.", contacts=1000,
                        rows=4000, stack=30000000)
    for thing in ET.parse(things_path).getroot():
        name = thing.find("ID").get("value")
        mass = float(thing.find("mass").get("value"))
        pos = xyz(thing.find("pos"))
        quat = rot_deg_quaternion(*xyz(thing.find("rot_deg")))
        if thing.tag == "cuboid":
            geom = f'type="box" size="{fmt(*(s / 2 for s in xyz(thing.find("size"))))}"'
        elif thing.tag == "sphere":
            geom = f'type="sphere" size="{float(thing.find("radius").get("value")):g}"'
        else:
            raise SystemExit(f"{things_path}: thing <{thing.tag}> not handled")
        lines.append(f'    <body name="{name}" pos="{fmt(*pos)}" quat="{fmt(*quat)}"><freejoint/>'
                     f'<geom {geom} mass="{mass:g}"/></body>')
    lines += ["  </worldbody>", "</mujoco>"]
    return "\n".join(lines) + "\n"


# Articulated models: boxes whose frames are aligned with the world at the start (centre =
# centre of mass), joined by hinges. One description written three ways: S2Sim's XML, MJCF and
# a table the ODE side reads (bench/peers/ode_engine.cpp).
HOLD = dict(ki=2.0, ri=2.0, imax=20.0, bv=0.1, fc=200.0, rotor_J=1e-3, volts=0.0)
PASSIVE = dict(ki=0.0, ri=1.0, imax=0.0, bv=0.0, fc=0.0, rotor_J=0.0, volts=0.0)


def box(name, size, centre, mass):
    return dict(name=name, size=size, centre=centre, mass=mass)


def hinge(name, child, parent, axis, anchor, drive, loop=False):
    return dict(name=name, child=child, parent=parent, axis=axis, anchor=anchor, drive=drive,
                loop=loop)


def humanoid():
    """A humanoid-sized tree: 21 boxes, 20 hinges, 64.5 kg, standing on its feet. Every hinge
    has a motor at 0 V and a Coulomb friction that holds it, except the shoulders' pitch, driven
    at 4 V against 0.5 N·m: the arms swing forward to about 18 degrees, where gravity balances
    the motor (at 12 V the swing toppled the figure, differently in each engine)."""
    bodies = [box("pelvis", (0.2, 0.3, 0.1), (0, 0, 1.05), 8.0)]
    joints = []
    arm_hold = dict(HOLD, fc=20.0)
    shoulder = dict(HOLD, fc=0.5, volts=4.0)
    for side, y in (("l", 0.1), ("r", -0.1)):
        bodies += [box(f"hip_{side}", (0.08, 0.08, 0.06), (0, y, 0.95), 1.0),
                   box(f"thigh_{side}", (0.1, 0.1, 0.4), (0, y, 0.7), 6.0),
                   box(f"shin_{side}", (0.08, 0.08, 0.4), (0, y, 0.27), 3.0),
                   box(f"foot_{side}", (0.24, 0.1, 0.05), (0.04, y, 0.025), 1.0)]
        joints += [hinge(f"hip_roll_{side}", f"hip_{side}", "pelvis", (1, 0, 0), (0, y, 1.0), HOLD),
                   hinge(f"hip_pitch_{side}", f"thigh_{side}", f"hip_{side}", (0, 1, 0), (0, y, 0.92), HOLD),
                   hinge(f"knee_{side}", f"shin_{side}", f"thigh_{side}", (0, 1, 0), (0, y, 0.485), HOLD),
                   hinge(f"ankle_{side}", f"foot_{side}", f"shin_{side}", (0, 1, 0), (0, y, 0.06), HOLD)]
    bodies += [box("abdomen", (0.2, 0.28, 0.15), (0, 0, 1.19), 6.0),
               box("chest", (0.22, 0.34, 0.3), (0, 0, 1.43), 14.0),
               box("neck", (0.06, 0.06, 0.08), (0, 0, 1.63), 0.5),
               box("head", (0.18, 0.16, 0.2), (0, 0, 1.78), 4.0)]
    joints += [hinge("waist", "abdomen", "pelvis", (0, 1, 0), (0, 0, 1.11), HOLD),
               hinge("chest_yaw", "chest", "abdomen", (0, 0, 1), (0, 0, 1.27), HOLD),
               hinge("neck_yaw", "neck", "chest", (0, 0, 1), (0, 0, 1.585), HOLD),
               hinge("head_pitch", "head", "neck", (0, 1, 0), (0, 0, 1.675), HOLD)]
    for side, y in (("l", 0.22), ("r", -0.22)):
        ys = 0.18 if y > 0 else -0.18
        bodies += [box(f"shoulder_{side}", (0.08, 0.08, 0.08), (0, y, 1.53), 1.0),
                   box(f"upper_arm_{side}", (0.07, 0.07, 0.3), (0, y, 1.33), 2.0),
                   box(f"forearm_{side}", (0.06, 0.06, 0.26), (0, y, 1.03), 1.5),
                   box(f"hand_{side}", (0.04, 0.08, 0.1), (0, y, 0.84), 0.5)]
        joints += [hinge(f"shoulder_roll_{side}", f"shoulder_{side}", "chest", (1, 0, 0), (0, ys, 1.53), arm_hold),
                   hinge(f"shoulder_pitch_{side}", f"upper_arm_{side}", f"shoulder_{side}", (0, 1, 0), (0, y, 1.49), shoulder),
                   hinge(f"elbow_{side}", f"forearm_{side}", f"upper_arm_{side}", (0, 1, 0), (0, y, 1.17), arm_hold),
                   hinge(f"wrist_{side}", f"hand_{side}", f"forearm_{side}", (1, 0, 0), (0, y, 0.895), arm_hold)]
    return dict(name="humanoid", root_free=True, bodies=bodies, joints=joints,
                comment="A humanoid-sized tree of 20 hinges standing on the floor.")


def four_bar_arm():
    """A parallelogram four-bar hung from the world (scenes/default's, cranks hanging straight
    down): crank A driven at 3 V raises the linkage to where its torque balances gravity (about
    30 degrees); hinge D closes the loop."""
    motor = dict(ki=2.0, ri=2.0, imax=10.0, bv=0.01, fc=0.01, rotor_J=1e-3, volts=3.0)
    bodies = [box("crank1", (0.03, 0.03, 0.4), (0, 0, 1.3), 0.5),
              box("crank2", (0.03, 0.03, 0.4), (0.5, 0, 1.3), 0.5),
              box("coupler", (0.5, 0.03, 0.03), (0.25, 0, 1.1), 1.0)]
    joints = [hinge("A", "crank1", "world", (0, 1, 0), (0, 0, 1.5), motor),
              hinge("B", "crank2", "world", (0, 1, 0), (0.5, 0, 1.5), PASSIVE),
              hinge("C", "coupler", "crank1", (0, 1, 0), (0, 0, 1.1), PASSIVE),
              hinge("D", "coupler", "crank2", (0, 1, 0), (0.5, 0, 1.1), PASSIVE, loop=True)]
    return dict(name="arm_loop", root_free=False, bodies=bodies, joints=joints,
                comment="A four-bar arm closed by a loop hinge, driven at crank A.")


def s2sim_articulated(model):
    lines = ["<?xml version='1.0' ?>",
             f"<!-- Made by bench/peers/make-peer-scenes.py; do not edit. {model['comment']} -->",
             "<robot>", f"  <kind value='{model['name']}'/>", "  <solids>"]
    for b in model["bodies"]:
        lines += ["    <cuboid>", f"      <ID value='{b['name']}'/>", f"      <mass value='{b['mass']:g}'/>",
                  "      <size x='{:g}' y='{:g}' z='{:g}'/>".format(*b["size"]),
                  "      <pos x='{:g}' y='{:g}' z='{:g}'/>".format(*b["centre"]), "    </cuboid>"]
    lines += ["  </solids>", "  <articulations>"]
    for j in model["joints"]:
        d = j["drive"]
        active = 1 if d["ki"] > 0 else 0
        motor = (f"      <motor ri='{d['ri']:g}' li='1e-9' ki='{d['ki']:g}' vmax='100' imax='{d['imax']:g}'"
                 f" active='{active}'/>") if active else "      <motor active='0'/>"
        lines += ["    <joint>", f"      <ID value='{j['name']}'/>", "      <type value='Hinge'/>",
                  f"      <connect B1='{j['child']}' B2='{j['parent']}'/>",
                  "      <pos x='{:g}' y='{:g}' z='{:g}'/>".format(*j["anchor"]),
                  "      <axis x='{:g}' y='{:g}' z='{:g}'/>".format(*j["axis"]), motor,
                  "      <gear ratio='1'/>", f"      <rotor J='{d['rotor_J']:g}'/>",
                  f"      <friction bv='{d['bv']:g}' fc='{d['fc']:g}'/>", "    </joint>"]
    lines += ["  </articulations>", "</robot>"]
    scene = ["<?xml version='1.0' ?>",
             f"<!-- Made by bench/peers/make-peer-scenes.py; do not edit. {model['comment']} -->",
             "<scene>", "  <s2sim>", "    <physics step_ms='1' substeps='1'/>", "  </s2sim>",
             "  <robot>", f"    <ID name='{model['name']}'/>", "    <pos x='0' y='0' z='0'/>",
             "    <body file='robot.xml'/>", "  </robot>", "</scene>"]
    return "\n".join(lines) + "\n", "\n".join(scene) + "\n"


def mjcf_articulated(model):
    bodies = {b["name"]: b for b in model["bodies"]}
    tree_joint = {j["child"]: j for j in model["joints"] if not j["loop"]}
    children = {}
    for j in model["joints"]:
        if not j["loop"]:
            children.setdefault(j["parent"], []).append(j["child"])
    lines = mjcf_header(model["name"], model["comment"])
    actuators = []

    def emit(name, parent_centre, indent):
        b = bodies[name]
        rel = [c - p for c, p in zip(b["centre"], parent_centre)]
        pad = " " * indent
        lines.append(f'{pad}<body name="{name}" pos="{fmt(*rel)}">')
        j = tree_joint.get(name)
        if j is None:
            lines.append(f"{pad}  <freejoint/>")
        else:
            d = j["drive"]
            damping = (d["ki"] * d["ki"] / d["ri"] if d["ki"] > 0 else 0.0) + d["bv"]
            anchor = [a - c for a, c in zip(j["anchor"], b["centre"])]
            lines.append(f'{pad}  <joint name="{j["name"]}" type="hinge" axis="{fmt(*j["axis"])}"'
                         f' pos="{fmt(*anchor)}" damping="{damping:.10g}" frictionloss="{d["fc"]:g}"'
                         f' armature="{d["rotor_J"]:g}"/>')
            if d["ki"] > 0:
                actuators.append(mjcf_motor(j["name"], d["ki"] / d["ri"], d["ki"] * d["imax"]))
        lines.append(f'{pad}  <geom type="box" size="{fmt(*(s / 2 for s in b["size"]))}" mass="{b["mass"]:g}"/>')
        for child in children.get(name, []):
            emit(child, b["centre"], indent + 2)
        lines.append(f"{pad}</body>")

    roots = [b["name"] for b in model["bodies"]
             if b["name"] not in tree_joint or tree_joint[b["name"]]["parent"] == "world"]
    for r in roots:
        emit(r, (0, 0, 0), 4)
    lines.append("  </worldbody>")
    loops = [j for j in model["joints"] if j["loop"]]
    if loops:
        lines.append("  <equality>")
        for j in loops:
            # A ball at the loop's anchor: in a planar linkage the hinges already keep the axes.
            anchor = [a - c for a, c in zip(j["anchor"], bodies[j["child"]]["centre"])]
            lines.append(f'    <connect name="{j["name"]}" body1="{j["child"]}" body2="{j["parent"]}"'
                         f' anchor="{fmt(*anchor)}"/>')
        lines.append("  </equality>")
        # MuJoCo excludes only parent-child pairs: the loop's two bodies would touch at D.
        lines.append("  <contact>")
        for j in loops:
            lines.append(f'    <exclude body1="{j["child"]}" body2="{j["parent"]}"/>')
        lines.append("  </contact>")
    lines += ["  <actuator>"] + actuators + ["  </actuator>", "</mujoco>"]
    return "\n".join(lines) + "\n"


def ode_table(model):
    index = {b["name"]: i for i, b in enumerate(model["bodies"])}
    index["world"] = -1
    lines = [f"# Made by bench/peers/make-peer-scenes.py; do not edit. {model['comment']}",
             "# body name mass sx sy sz cx cy cz  (box, frame aligned with the world at the centre)",
             "# hinge name child parent ax ay az px py pz ki ri imax bv fc rotor_J volts"]
    for b in model["bodies"]:
        lines.append(f"body {b['name']} {b['mass']:g} {fmt(*b['size'])} {fmt(*b['centre'])}")
    for j in model["joints"]:
        d = j["drive"]
        lines.append(f"hinge {j['name']} {index[j['child']]} {index[j['parent']]} {fmt(*j['axis'])}"
                     f" {fmt(*j['anchor'])} {d['ki']:g} {d['ri']:g} {d['imax']:g} {d['bv']:g} {d['fc']:g}"
                     f" {d['rotor_J']:g} {d['volts']:g}")
    return "\n".join(lines) + "\n"


def write_robots(out, counts):
    here = os.path.dirname(os.path.abspath(__file__))
    os.makedirs(os.path.join(out, "scenes"), exist_ok=True)
    # The scenes name their robot as ../diffbot.xml, as the committed ones do.
    shutil.copyfile(os.path.join(here, "scenes", "diffbot.xml"),
                    os.path.join(out, "scenes", "diffbot.xml"))
    for n in counts:
        write(os.path.join(out, "scenes", f"robots_{n}", "scene.xml"), s2sim_robots_scene(n))
        write(os.path.join(out, "mjcf", f"robots_{n}.xml"), mjcf_robots(n))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", help="write only the robots_N of --robots, under this folder")
    parser.add_argument("--robots", type=int, nargs="+", default=list(LARGE_ROBOT_COUNTS),
                        metavar="N", help="robot counts for --out (default: %(default)s)")
    args = parser.parse_args()
    if args.out:
        if any(n <= 0 for n in args.robots):
            parser.error("--robots: counts must be positive")
        write_robots(args.out, args.robots)
        return
    for n in ROBOT_COUNTS:
        write(f"bench/peers/scenes/robots_{n}/scene.xml", s2sim_robots_scene(n))
        write(f"bench/peers/mjcf/robots_{n}.xml", mjcf_robots(n))
    write("bench/peers/mjcf/pile.xml", mjcf_pile("scenes/pile/things.xml"))
    for model in (humanoid(), four_bar_arm()):
        robot, scene = s2sim_articulated(model)
        write(f"bench/peers/scenes/{model['name']}/robot.xml", robot)
        write(f"bench/peers/scenes/{model['name']}/scene.xml", scene)
        write(f"bench/peers/mjcf/{model['name']}.xml", mjcf_articulated(model))
        write(f"bench/peers/scenes/{model['name']}/model.txt", ode_table(model))
    print("wrote", len(ROBOT_COUNTS), "robot scenes, their MJCF and the pile's MJCF")


if __name__ == "__main__":
    main()
