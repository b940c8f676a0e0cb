{ SimTwo's axis points for scripts (written for S2Sim after SimTwo's behaviour; no SimTwo
  source): the trajectory points a script keeps per axis, and the joint waypoints: per robot a
  list of named states, per axis its points (pos, speed, final_time), read from and written to
  SimTwo's <joint_waypoints> files. A relative file name is taken in the
  script's folder, as SimTwo's working folder is the project's. }
unit s2simtwo_waypoints;

{$mode delphi}{$H+}

interface

uses SysUtils, Classes, Math, DOM, XMLRead, XMLWrite, s2simtwo_types, s2simtwo;

procedure LoadJointWayPoints(r: integer; JointPointsFileName: string);
procedure SaveJointWayPoints(r: integer; JointPointsFileName: string);
function CountJointWayPoints(R, i: integer): integer;
function GetJointWayPoint(R, i, idx: integer): TAxisPoint;
procedure SetJointWayPoint(R, i, idx: integer; apos, aspeed, atime: double);
function GetAxisTrajPoint(R, i, idx: integer): TAxisPoint;
procedure SetAxisTrajPoint(R, i, idx: integer; LP: TAxisPoint);
procedure AddAxisTrajPoint(R, i: integer; LP: TAxisPoint);
procedure DelAxisTrajPoint(R, i, idx: integer);
function CountAxisTrajPoints(R, i: integer): integer;
procedure ClearAxisTrajPoints(R, i: integer);

implementation

type
  TRobotWayPoints = record
    R: integer;
    ids: array of string;             { the states' IDs, in order }
    axes: array of array of TAxisPoint;  { per axis, one point a state }
  end;

var
  Robots: array of TRobotWayPoints;

function RobotOf(R: integer): integer;
var k: integer;
begin
  for k := 0 to High(Robots) do
    if Robots[k].R = R then begin result := k; exit; end;
  result := Length(Robots);
  SetLength(Robots, result + 1);
  Robots[result].R := R;
  SetLength(Robots[result].axes, S2SimAxisCount(R));  { raises for a robot that does not exist }
end;

function AxisOf(R, i: integer): integer;
begin
  result := RobotOf(R);
  if (i < 0) or (i > High(Robots[result].axes)) then
    raise EScriptHostError.Create(SysUtils.Format('List index (%d) out of bounds', [i]));
end;

function Attribute(node: TDOMNode; const name, default: string): string;
var a: TDOMNode;
begin
  result := default;
  if node.Attributes = nil then exit;
  a := node.Attributes.GetNamedItem(name);
  if a <> nil then result := a.NodeValue;
end;

function Number(node: TDOMNode; const name: string; default: double): double;
begin
  result := StrToFloatDef(Attribute(node, name, ''), default);
end;

procedure AddPoint(k, axis: integer; pos, speed, t: double);
var n: integer;
begin
  n := Length(Robots[k].axes[axis]);
  SetLength(Robots[k].axes[axis], n + 1);
  Robots[k].axes[axis][n].pos := pos;
  Robots[k].axes[axis][n].speed := speed;
  Robots[k].axes[axis][n].final_time := t;
end;

{ As SimTwo: each state's joints get its point (theta in degrees; w as written, SimTwo does not
  convert it), then every axis the state did not name repeats its last point (or 0, 0) at the
  state's time. The earlier points are cleared first. }
procedure LoadJointWayPoints(r: integer; JointPointsFileName: string);
var k, a, which, n: integer; doc: TXMLDocument; state, joint: TDOMNode; t, pos, speed: double;
    file_: string;
begin
  k := RobotOf(r);
  SetLength(Robots[k].ids, 0);
  for a := 0 to High(Robots[k].axes) do SetLength(Robots[k].axes[a], 0);
  file_ := InScriptFolder(JointPointsFileName);
  try
    ReadXMLFile(doc, file_);
  except
    on E: Exception do
      raise EScriptHostError.Create('LoadJointWayPoints: cannot read ' + file_ + ': ' + E.Message);
  end;
  try
    if (doc.DocumentElement = nil) or (doc.DocumentElement.NodeName <> 'joint_waypoints') then
      raise EScriptHostError.Create('LoadJointWayPoints: ' + file_ + ' has no <joint_waypoints> root');
    state := doc.DocumentElement.FirstChild;
    while state <> nil do begin
      if state.NodeName = 'state' then begin
        t := Number(state, 'final_time', 0);
        joint := state.FirstChild;
        while joint <> nil do begin
          if joint.NodeName = 'joint' then begin
            which := StrToIntDef(Attribute(joint, 'axis', '1'), 1) - 1;
            a := GetAxisIndex(r, Attribute(joint, 'ID', '-1'), which);
            pos := DegToRad(Number(joint, 'theta', 0));
            speed := Number(joint, 'w', 0);
            if a >= 0 then AddPoint(k, a, pos, speed, t);
          end;
          joint := joint.NextSibling;
        end;
        n := Length(Robots[k].ids);
        SetLength(Robots[k].ids, n + 1);
        Robots[k].ids[n] := Attribute(state, 'ID', '');
        for a := 0 to High(Robots[k].axes) do begin
          n := Length(Robots[k].axes[a]);
          if (n > 0) and (abs(Robots[k].axes[a][n - 1].final_time - t) < 1e-5) then continue;
          if n > 0 then AddPoint(k, a, Robots[k].axes[a][n - 1].pos, Robots[k].axes[a][n - 1].speed, t)
          else AddPoint(k, a, 0, 0, t);
        end;
      end;
      state := state.NextSibling;
    end;
  finally
    doc.Free;
  end;
end;

{ As SimTwo: a state per ID, its time the first axis's; a joint is written when it changed since
  the state before (1e-8), theta and w in degrees; `axis` only for a joint's second axis. }
procedure SaveJointWayPoints(r: integer; JointPointsFileName: string);
var k, s, a, which: integer; doc: TXMLDocument; root, state, joint: TDOMElement;
    id: string; p, q: TAxisPoint;
begin
  k := RobotOf(r);
  if Length(Robots[k].axes) = 0 then exit;
  doc := TXMLDocument.Create;
  try
    root := doc.CreateElement('joint_waypoints');
    doc.AppendChild(root);
    for s := 0 to High(Robots[k].ids) do begin
      state := doc.CreateElement('state');
      state.SetAttribute('ID', Robots[k].ids[s]);
      if s <= High(Robots[k].axes[0]) then
        state.SetAttribute('final_time', SysUtils.Format('%g', [Robots[k].axes[0][s].final_time]));
      root.AppendChild(state);
      for a := 0 to High(Robots[k].axes) do begin
        if s > High(Robots[k].axes[a]) then continue;
        p := Robots[k].axes[a][s];
        if s > 0 then begin
          q := Robots[k].axes[a][s - 1];
          if (abs(q.pos - p.pos) < 1e-8) and (abs(q.speed - p.speed) < 1e-8) then continue;
        end;
        id := S2SimAxisJoint(r, a, which);
        joint := doc.CreateElement('joint');
        joint.SetAttribute('ID', id);
        if which <> 0 then joint.SetAttribute('axis', IntToStr(which + 1));
        joint.SetAttribute('theta', SysUtils.Format('%g', [RadToDeg(p.pos)]));
        joint.SetAttribute('w', SysUtils.Format('%g', [RadToDeg(p.speed)]));
        state.AppendChild(joint);
      end;
    end;
    try
      WriteXMLFile(doc, InScriptFolder(JointPointsFileName));
    except
      on E: Exception do
        raise EScriptHostError.Create('SaveJointWayPoints: cannot write ' +
          InScriptFolder(JointPointsFileName) + ': ' + E.Message);
    end;
  finally
    doc.Free;
  end;
end;

function CountJointWayPoints(R, i: integer): integer;
var k: integer;
begin
  k := RobotOf(R);
  result := Length(Robots[k].axes[AxisOf(R, i)]);
end;

function Point(R, i, idx: integer): integer;
begin
  result := RobotOf(R);
  if (idx < 0) or (idx > High(Robots[result].axes[AxisOf(R, i)])) then
    raise EScriptHostError.Create(SysUtils.Format('List index (%d) out of bounds', [idx]));
end;

function GetJointWayPoint(R, i, idx: integer): TAxisPoint;
begin
  result := Robots[Point(R, i, idx)].axes[i][idx];
end;

procedure SetJointWayPoint(R, i, idx: integer; apos, aspeed, atime: double);
var k: integer;
begin
  k := Point(R, i, idx);
  Robots[k].axes[i][idx].pos := apos;
  Robots[k].axes[i][idx].speed := aspeed;
  Robots[k].axes[i][idx].final_time := atime;
end;

{ An axis's trajectory points: lists the script keeps and reads back, one per axis. }
type
  TAxisTraj = record
    R, i: integer;
    points: array of TAxisPoint;
  end;
var
  AxisTrajs: array of TAxisTraj;

function AxisTraj(R, i: integer): integer;
var k: integer;
begin
  for k := 0 to High(AxisTrajs) do
    if (AxisTrajs[k].R = R) and (AxisTrajs[k].i = i) then begin result := k; exit; end;
  GetAxisPos(R, i);  { raises SimTwo's index error for an axis that does not exist }
  result := Length(AxisTrajs);
  SetLength(AxisTrajs, result + 1);
  AxisTrajs[result].R := R;
  AxisTrajs[result].i := i;
end;

function TrajPoint(R, i, idx: integer): integer;
begin
  result := AxisTraj(R, i);
  if (idx < 0) or (idx > High(AxisTrajs[result].points)) then
    raise EScriptHostError.Create(SysUtils.Format('List index (%d) out of bounds', [idx]));
end;

function GetAxisTrajPoint(R, i, idx: integer): TAxisPoint;
begin result := AxisTrajs[TrajPoint(R, i, idx)].points[idx]; end;
procedure SetAxisTrajPoint(R, i, idx: integer; LP: TAxisPoint);
begin AxisTrajs[TrajPoint(R, i, idx)].points[idx] := LP; end;
procedure AddAxisTrajPoint(R, i: integer; LP: TAxisPoint);
var k, n: integer;
begin
  k := AxisTraj(R, i);
  n := Length(AxisTrajs[k].points);
  SetLength(AxisTrajs[k].points, n + 1);
  AxisTrajs[k].points[n] := LP;
end;
procedure DelAxisTrajPoint(R, i, idx: integer);
var k, j: integer;
begin
  k := AxisTraj(R, i);
  if (idx < 0) or (idx > High(AxisTrajs[k].points)) then exit;  { SimTwo ignores it too }
  for j := idx to High(AxisTrajs[k].points) - 1 do AxisTrajs[k].points[j] := AxisTrajs[k].points[j + 1];
  SetLength(AxisTrajs[k].points, Length(AxisTrajs[k].points) - 1);
end;
function CountAxisTrajPoints(R, i: integer): integer; begin result := Length(AxisTrajs[AxisTraj(R, i)].points); end;
procedure ClearAxisTrajPoints(R, i: integer); begin SetLength(AxisTrajs[AxisTraj(R, i)].points, 0); end;

end.
