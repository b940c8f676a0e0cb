#!/usr/bin/env python3
"""Writes the Bioloid-like humanoid of the SimTwo paper (section 4.2): the robot
scenes/humanoid/humanoid.xml and its walking gait's key poses, as the joint-angle table of
scenes/humanoid/control.pas and of python/examples/humanoid_gait.py (the same numbers, so
that the script and the Python controller drive the same trajectory bit for bit).

The gait is written in feet positions relative to the hips (x forward, y left, z up) and turned
into joint angles here, by the legs' inverse kinematics: the script only interpolates joint
angles between key poses, as the paper's "trajectory states". Run from the repository root:
    python3 scripts/make-humanoid.py
"""
import math
import re

# --- Geometry (m). Forward is +x, left +y. Each body's mass stands for its servos (an AX-12
# is 55 g) and brackets; the whole robot weighs 1.975 kg.
HIP_Y = 0.037  # lateral offset of each leg
ANKLE_Z, KNEE_Z, HIP_Z, YAW_Z = 0.03, 0.105, 0.18, 0.21
THIGH = HIP_Z - KNEE_Z  # 0.075
SHIN = KNEE_Z - ANKLE_Z  # 0.075

# --- The AX-12 (docs/models/dc-motor.md, "Servo"): stall torque 1.5 N·m and no-load speed
# 59 rpm = 6.18 rad/s at 12 V (Robotis' AX-12A e-manual). The feedback gains are the scene's
# args (scene.xml). The joint's friction stands for the gearbox's.
TORQUE_MAX = 1.5
SPEED_MAX = 6.18
FRICTION_BV, FRICTION_FC = 0.02, 0.01

solids = []  # (id, mass, size, pos, colour)
joints = []  # (id, child, parent, pos, axis)


def solid(name, mass, size, pos, colour=(60, 60, 60)):
    solids.append((name, mass, size, pos, colour))


def joint(name, child, parent, pos, axis):
    joints.append((name, child, parent, pos, axis))


solid('trunk', 0.575, (0.07, 0.11, 0.12), (0, 0, 0.275), (200, 200, 210))
for side, sy in (('l', 1), ('r', -1)):
    y = sy * HIP_Y
    solid(f'hip_yaw_{side}', 0.055, (0.03, 0.03, 0.015), (0, y, 0.2))
    solid(f'hip_roll_{side}', 0.055, (0.02, 0.03, 0.02), (0, y, HIP_Z))
    solid(f'thigh_{side}', 0.13, (0.03, 0.04, 0.055), (0, y, 0.1375), (200, 200, 210))
    solid(f'shin_{side}', 0.10, (0.03, 0.04, 0.06), (0, y, 0.075), (200, 200, 210))
    solid(f'ankle_{side}', 0.03, (0.02, 0.03, 0.02), (0, y, ANKLE_Z))
    solid(f'foot_{side}', 0.12, (0.11, 0.066, 0.012), (0.01, y, 0.006), (40, 40, 40))
for side, sy in (('l', 1), ('r', -1)):
    solid(f'shoulder_{side}', 0.055, (0.025, 0.02, 0.025), (0, sy * 0.07, 0.315))
    solid(f'upper_arm_{side}', 0.07, (0.025, 0.025, 0.06), (0, sy * 0.085, 0.27),
          (200, 200, 210))
    solid(f'forearm_{side}', 0.05, (0.025, 0.025, 0.055), (0, sy * 0.085, 0.2), (200, 200, 210))
solid('head', 0.07, (0.05, 0.05, 0.045), (0, 0, 0.3625), (230, 120, 40))

# Joint order is the script's axis order. Hip pitch turns about -y so that a positive angle
# swings the foot forward; knee and ankle pitch about +y (a positive knee bends it backward).
for side, sy in (('l', 1), ('r', -1)):
    y = sy * HIP_Y
    joint(f'hip_yaw_{side}', f'hip_yaw_{side}', 'trunk', (0, y, YAW_Z), (0, 0, 1))
    joint(f'hip_roll_{side}', f'hip_roll_{side}', f'hip_yaw_{side}', (0, y, HIP_Z), (1, 0, 0))
    joint(f'hip_pitch_{side}', f'thigh_{side}', f'hip_roll_{side}', (0, y, HIP_Z), (0, -1, 0))
    joint(f'knee_{side}', f'shin_{side}', f'thigh_{side}', (0, y, KNEE_Z), (0, 1, 0))
    joint(f'ankle_pitch_{side}', f'ankle_{side}', f'shin_{side}', (0, y, ANKLE_Z), (0, 1, 0))
    joint(f'ankle_roll_{side}', f'foot_{side}', f'ankle_{side}', (0, y, ANKLE_Z), (1, 0, 0))
for side, sy in (('l', 1), ('r', -1)):
    joint(f'shoulder_pitch_{side}', f'shoulder_{side}', 'trunk', (0, sy * 0.065, 0.315),
          (0, -1, 0))
    joint(f'shoulder_roll_{side}', f'upper_arm_{side}', f'shoulder_{side}',
          (0, sy * 0.075, 0.315), (1, 0, 0))
    joint(f'elbow_{side}', f'forearm_{side}', f'upper_arm_{side}', (0, sy * 0.085, 0.235),
          (0, -1, 0))
joint('neck', 'head', 'trunk', (0, 0, 0.335), (0, 0, 1))
AXES = [j[0] for j in joints]


def num(v):
    return f'{v:.6g}'


def robot_xml():
    out = ['<?xml version="1.0" ?>',
           '<!-- A Bioloid-like humanoid (SimTwo paper, section 4.2), written by',
           '     scripts/make-humanoid.py: 1.975 kg, 0.385 m tall, 19 AX-12 servos (six per leg:',
           '     hip yaw, roll, pitch, knee, ankle pitch, roll; three per arm: shoulder pitch,',
           '     roll, elbow; one in the neck). Every body is a box whose mass stands for its',
           '     servos and brackets; the feet are flat boxes. Forward is +x, left +y. -->',
           '<robot>', '  <solids>']
    for name, mass, size, pos, colour in solids:
        surface = "\n      <surface mu='1' mu2='1'/>" if name.startswith('foot') else ''
        out.append(f"""    <cuboid>
      <ID value='{name}'/>
      <mass value='{num(mass)}'/>
      <size x='{num(size[0])}' y='{num(size[1])}' z='{num(size[2])}'/>
      <pos x='{num(pos[0])}' y='{num(pos[1])}' z='{num(pos[2])}'/>
      <color_rgb r='{colour[0]}' g='{colour[1]}' b='{colour[2]}'/>{surface}
    </cuboid>""")
    out += ['  </solids>', '  <articulations>', '    <default>',
            "      <!-- The servo plugin is the motor; the joint keeps the gearbox's friction. -->",
            "      <motor active='0'/>",
            f"      <friction bv='{num(FRICTION_BV)}' fc='{num(FRICTION_FC)}'/>",
            '    </default>']
    for name, child, parent, pos, axis in joints:
        out.append(f"""    <joint>
      <ID value='{name}'/>
      <type value='Hinge'/>
      <connect B1='{child}' B2='{parent}'/>
      <pos x='{num(pos[0])}' y='{num(pos[1])}' z='{num(pos[2])}'/>
      <axis x='{axis[0]}' y='{axis[1]}' z='{axis[2]}'/>
    </joint>""")
    out.append('  </articulations>')
    out.append(f'  <!-- AX-12 at 12 V: {TORQUE_MAX} N·m stall torque, {SPEED_MAX} rad/s '
               '(59 rpm) no-load speed, ±150°. -->')
    for name in AXES:
        gains = 'kp_leg' if name[:3] in ('hip', 'kne', 'ank') else 'kp_arm'
        kd = gains.replace('kp', 'kd')
        out.append(f"  <plugin kind='servo' id='{name}_servo' axis='{name}' kp='{gains}' kd='{kd}' "
                   f"torque_max='{TORQUE_MAX}' speed_max='{SPEED_MAX}' armature='armature'/>")
    out.append('</robot>')
    return '\n'.join(out) + '\n'


# --- The gait. Each leg's key: ankle position relative to its hip point (x, y, z).
STAND_Z = -0.132  # crouched: the knees bent 57°, the hips 18 mm lower than straight
SHIFT_Y = 0.046  # hips over the stance foot
LIFT = 0.02  # swing foot clearance
STEP = 0.06
# Durations of the phases in script periods (20 ms).
T_CROUCH, T_SHIFT, T_LIFT, T_SWING, T_LOWER = 50, 35, 12, 18, 12


def leg_angles(x, y, z):
    """Hip roll, hip pitch, knee, ankle pitch, ankle roll (deg) putting the ankle at (x, y, z)
    from the hip with the foot flat; the knee bends forward. The rear leg of the longest steps
    is out of reach by a few mm: it gets the straight leg pointing at the ankle."""
    roll = math.atan2(y, -z)
    h = math.hypot(y, z)
    d = math.hypot(x, h)
    bend = math.acos(min(1.0, d / (2 * THIGH)))  # out of reach: the straight leg toward it
    lean = math.atan2(x, h)
    thigh, shin = lean + bend, lean - bend  # from the vertical, forward positive
    deg = math.degrees
    return deg(roll), deg(thigh), deg(thigh - shin), deg(shin), -deg(roll)


def pose(left, right):
    """Joint angles (deg, in AXES order) for the two ankles' positions; arms and head still."""
    angles = []
    for x, y, z in (left, right):
        roll, hp, kn, ap, ar = leg_angles(x, y, z)
        angles += [0.0, roll, hp, kn, ap, ar]
    angles += [0.0, 0.0, 0.0] * 2 + [0.0]
    return [round(a, 2) + 0.0 for a in angles]


def gait():
    """Key poses (pose, duration in script periods): a crouch, the weight over the left foot and
    a first half step of the right leg, then one cycle (a step of each leg) that repeats from
    the index returned. Each leg's ankle is given relative to its hip point."""
    s, z, up, w = STEP, STAND_Z, STAND_Z + LIFT, SHIFT_Y
    keys = [(pose((0, 0, -0.15), (0, 0, -0.15)), 1),
            (pose((0, 0, z), (0, 0, z)), T_CROUCH),
            (pose((0, -w, z), (0, -w, z)), T_SHIFT),
            (pose((0, -w, z), (0, -w, up)), T_LIFT),
            (pose((0, -w, z), (s, -w, up)), T_SWING),
            (pose((0, -w, z), (s, -w, z)), T_LOWER)]
    loop = len(keys)
    # The hips move over the right foot and forward by STEP (the feet go back by STEP); the
    # left foot lifts, swings 2·STEP forward and comes down; then the same mirrored.
    keys += [(pose((-s, w, z), (0, w, z)), T_SHIFT),
             (pose((-s, w, up), (0, w, z)), T_LIFT),
             (pose((s, w, up), (0, w, z)), T_SWING),
             (pose((s, w, z), (0, w, z)), T_LOWER),
             (pose((0, -w, z), (-s, -w, z)), T_SHIFT),
             (pose((0, -w, z), (-s, -w, up)), T_LIFT),
             (pose((0, -w, z), (s, -w, up)), T_SWING),
             (pose((0, -w, z), (s, -w, z)), T_LOWER)]
    return keys, loop


def patch(path, begin, end, body):
    text = open(path).read()
    pattern = re.compile(re.escape(begin) + '.*?' + re.escape(end), re.S)
    if not pattern.search(text):
        raise SystemExit(f'{path}: no {begin!r} ... {end!r} block')
    open(path, 'w').write(pattern.sub(lambda _: begin + '\n' + body + end, text))


def main():
    with open('scenes/humanoid/humanoid.xml', 'w') as f:
        f.write(robot_xml())
    keys, loop = gait()
    poses = [k[0] for k in keys]
    durations = [k[1] for k in keys]
    rows = ',\n'.join('    (' + ', '.join(f'{a:.2f}' for a in p) + ')' for p in poses)
    listed = ', '.join(map(str, durations))
    pas = (f'const\n  PoseCount = {len(poses)};\n  LoopStart = {loop};\n'
           f'  Durations: array[0..PoseCount - 1] of integer = ({listed});\n'
           f'  Poses: array[0..PoseCount - 1, 0..AxisCount - 1] of double = (\n{rows});\n')
    patch('scenes/humanoid/control.pas', '// BEGIN key poses', '// END key poses', pas)
    py_rows = ',\n'.join('    (' + ', '.join(f'{a:.2f}' for a in p) + ')' for p in poses)
    py = ('AXES = (\n' + ''.join(f'    "{a}",\n' for a in AXES) + ')\n'
          f'LOOP_START = {loop}\nDURATIONS = ({listed})\n'
          f'POSES = (\n{py_rows},\n)\n')
    patch('python/examples/humanoid_gait.py', '# BEGIN key poses', '# END key poses', py)
    print(f'{len(solids)} bodies, {sum(s[1] for s in solids):.3f} kg, {len(joints)} servos, '
          f'{len(poses)} key poses, a cycle of '
          f'{sum(durations[loop:]) * 0.02:.2f} s advancing {2 * STEP} m')


if __name__ == '__main__':
    main()
