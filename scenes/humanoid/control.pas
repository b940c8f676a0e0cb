// The humanoid's walk (SimTwo paper, section 4.2): predefined key poses of the 19 servos,
// interpolated per servo ("trajectory states"). Each key pose is reached in its duration
// (script periods) along a smoothstep, u*u*(3 - 2*u), from the previous one; after the crouch
// and the first half step the cycle from LoopStart repeats. The table is written by
// scripts/make-humanoid.py, which also writes the same numbers into
// python/examples/humanoid_gait.py: only products and sums of doubles, so that the Python
// controller (python/examples/humanoid_walk.py) drives the same goals bit for bit.
const
  AxisCount = 19;
  // Typed, so a double: an untyped real constant is an 80-bit extended in fpc, and the
  // products with it would not be Python's.
  DegToRad: double = 0.017453292519943295;

// BEGIN key poses
const
  PoseCount = 14;
  LoopStart = 6;
  Durations: array[0..PoseCount - 1] of integer = (1, 50, 35, 12, 18, 12, 35, 12, 18, 12, 35, 12, 18, 12);
  Poses: array[0..PoseCount - 1, 0..AxisCount - 1] of double = (
    (0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, 0.00, 28.36, 56.72, -28.36, 0.00, 0.00, 0.00, 28.36, 56.72, -28.36, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -22.33, 36.18, 72.36, -36.18, 22.33, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -22.33, 52.09, 51.46, 0.63, 22.33, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -19.21, 23.23, 0.00, 23.23, 19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, 19.21, -23.23, 0.00, -23.23, -19.21, 0.00, 19.21, 21.27, 42.53, -21.27, -19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, 22.33, -0.63, 51.46, -52.09, -22.33, 0.00, 19.21, 21.27, 42.53, -21.27, -19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, 22.33, 52.09, 51.46, 0.63, -22.33, 0.00, 19.21, 21.27, 42.53, -21.27, -19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, 19.21, 23.23, 0.00, 23.23, -19.21, 0.00, 19.21, 21.27, 42.53, -21.27, -19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -19.21, -23.23, 0.00, -23.23, 19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -22.33, -0.63, 51.46, -52.09, 22.33, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -22.33, 52.09, 51.46, 0.63, 22.33, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00),
    (0.00, -19.21, 21.27, 42.53, -21.27, 19.21, 0.00, -19.21, 23.23, 0.00, 23.23, 19.21, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00, 0.00));
// END key poses

var
  pose, ticks: integer;

procedure Initialize;
begin
  pose := 0;
  ticks := 0;
end;

procedure Control;
var
  i, from: integer;
  elapsed, duration, u, s: double;
begin
  ticks := ticks + 1;
  if ticks > Durations[pose] then begin
    ticks := 1;
    pose := pose + 1;
    if pose >= PoseCount then pose := LoopStart;
  end;
  // The pose before LoopStart equals the cycle's last one, so the cycle joins smoothly.
  if pose = 0 then from := 0 else from := pose - 1;
  elapsed := ticks;
  duration := Durations[pose];
  u := elapsed / duration;
  s := u * u * (3 - 2 * u);
  for i := 0 to AxisCount - 1 do
    SetAxisPosRef(0, i, (Poses[from, i] + (Poses[pose, i] - Poses[from, i]) * s) * DegToRad);
end;
