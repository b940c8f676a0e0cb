{ S2Sim's SimTwo script host unit (written for S2Sim; no SimTwo source). It gives a SimTwo
  `control.pas`, compiled unchanged with Free Pascal -Mdelphi, the host functions, each
  forwarding to the C++ host through one table filled at load (plugins/pascal_script/
  host_calls.cpp), SimTwo's TStringList, Time and HUDStrings. It comes after the RTL in the
  wrapper's `uses`, so its names shadow the RTL's (docs/scripting.md); the other support units
  hold the types, Matrix, the pure helpers, A*, rendering and the axis points. }
unit s2simtwo;

{$mode delphi}{$H+}

interface

uses SysUtils, Classes, Math, Types, s2simtwo_types, s2simtwo_matrix, s2simtwo_helpers;

{S2SIM_HOST_IDS}

type
  { SimTwo (Windows) joins lines with CR LF; FPC on Linux with LF. Setting Text splits on
    LF, CR LF or CR alike, as SimTwo's does: FPC splits on LineBreak alone once it differs
    from the platform's, so an LF-only datagram would stay one line. }
  TStringList = class(Classes.TStringList)
  protected
    procedure SetTextStr(const Value: string); override;
  public
    constructor Create;
  end;

  { The host table: one entry for every host function (by id), filled by the C++ side. }
  THostCall = function(host: Pointer; fn: longint; args: PDouble; nargs: longint;
    text: PChar; textlen: longint; text2: PChar; text2len: longint): double; cdecl;
  { kind 0: the text result of the last call; 1: its numbers; 2: the error it raised. }
  THostResult = function(host: Pointer; kind: longint; out data: Pointer): longint; cdecl;
  PHostTable = ^THostTable;
  THostTable = record
    host: Pointer;
    call: THostCall;
    result: THostResult;
  end;

var
  Time: double;
  HUDStrings: TStringList;
  UDPDataRead: TMemoryStream;  { SimTwo's: the bytes received that ReadUDPData has not taken }
  Host: THostTable;

{ --- host functions (S2Sim's implementation: plugins/pascal_script/host_api.cpp) --- }
procedure WriteLn(S: string);
function KeyPressed(k: integer): Boolean;
function ScriptPeriod: double;
function GetSceneConstant(constantName: string; defaultValue: double): double;

procedure SetRCValue(r, c: integer; s: string);
function GetRCValue(r, c: integer): double;
function GetRCText(r, c: integer): string;
function RCButtonPressed(r, c: integer): boolean;
procedure ClearButtons;
procedure RefreshSheets;
procedure MatrixToRange(r, c: integer; const M: Matrix);
procedure MatrixToRangeF(r, c: integer; const M: Matrix; FormatString: string);
function RangeToMatrix(r, c, rows, cols: integer): Matrix;

function GetRobotIndex(ID: string): integer;
function GetSolidIndex(R: integer; ID: string): integer;
function GetSensorIndex(R: integer; ID: string): integer;
function GetAxisIndex(R: integer; ID: string; i: integer): integer;
function GetGlobalSensorIndex(ID: string): integer;
function GetThingIndex(ID: string): integer;
function GetThingsCount: integer;

procedure SetAxisVoltageRef(R, i: integer; aVoltage: double);
procedure SetAxisSpeedRef(R, i: integer; aSpeed: double);
procedure SetAxisPosRef(R, i: integer; aPos: double);
procedure SetAxisTorqueRef(R, i: integer; aTorque: double);
function GetAxisPosRef(R, i: integer): double;
function GetAxisSpeedRef(R, i: integer): double;
function GetAxisOdo(R, i: integer): integer;
function GetAxisPos(R, i: integer): double;
function GetAxisPosDeg(R, i: integer): double;
function GetAxisSpeed(R, i: integer): double;
function GetAxisSpeedDeg(R, i: integer): double;
function GetAxisI(R, i: integer): double;
function GetAxisU(R, i: integer): double;
function GetAxisTorque(R, i: integer): double;
function GetAxisState(R, i: integer): TAxisState;
procedure SetMotorActive(R, i: integer; nState: boolean);
function IsMotorActive(R, i: integer): boolean;
procedure SetMotorControllerState(R, i: integer; newState: boolean);
function GetMotorControllerState(R, i: integer): boolean;
function GetMotorPars(R, i: integer): TMotorPars;
procedure SetMotorPars(R, i: integer; aMotorPars: TMotorPars);

function GetSensorVal(R, i: integer): double;
function GetSensorValues(R, i: integer): Matrix;
procedure SetSensorVin(R, i: integer; Vin: byte);
function GetGlobalSensorVal(i: integer): double;
function GetGlobalSensorValues(i: integer): Matrix;

procedure SetRobotPos(R: integer; x, y, z, teta: double);
function GetRobotX(R: integer): double;
function GetRobotY(R: integer): double;
function GetRobotTheta(R: integer): double;
function GetRobotVx(R: integer): double;
function GetRobotVy(R: integer): double;
function GetRobotW(R: integer): double;
function GetRobotPos2D(R: integer): TState2D;
function GetSolidPos(R, i: integer): TPoint3D;
function GetSolidX(R, i: integer): double;
function GetSolidY(R, i: integer): double;
function GetSolidZ(R, i: integer): double;
function GetSolidTheta(R, i: integer): double;
function GetSolidPosMat(R, i: integer): Matrix;
function GetSolidRotMat(R, i: integer): Matrix;
function GetSolidLinearVel(R, i: integer): TPoint3D;
procedure SetSolidPos(R, i: integer; x, y, z: double);
procedure SetSolidRotationMat(R, i: integer; Rot: Matrix);
procedure SetSolidLinearVel(R, i: integer; x, y, z: double);
procedure SetSolidAngularVel(R, i: integer; x, y, z: double);
procedure SetSolidColor(R, I: integer; Red, Green, Blue: byte);
procedure SetShellTag(R, i: integer; newTag: string);
function GetShellTag(R, i: integer): string;

procedure SetThingPos(T: integer; x, y, z: double);
function GetThingPos(T: integer): TPoint3D;
function GetThingColor(T, c: integer): TRGBAColor;
function GetObstaclePos(T: integer): TPoint3D;
function AddOBstacleBox(ID: string; posx, posY, posZ, sizeX, sizeY, sizeZ: double; rgb24: integer): integer;
procedure ClearObstacles;

procedure ChartSeriesSetCount(ChartIndex, SeriesCount: integer);
procedure ChartSeriesSetColor(ChartIndex, SeriesIndex: integer; newColor: TColor);
procedure ChartSeriesClear(ChartIndex, SeriesIndex: integer);
procedure ChartSeriesAddXY(ChartIndex, SeriesIndex: integer; X, Y: double);

procedure AddTrailNode(T: integer; x, y, z: double);
procedure ClearTrail(T: integer);

procedure WriteUDPData(ToIP: string; ToPort: integer; s: string);
function ReadUDPData: string;
procedure WriteComPort(s: string);
function ReadComPort: string;

{ --- routines added for SimTwo's whole list (docs/scripting.md, coverage) --- }
function RGBToColor(R, G, B: Byte): TColor;
procedure SetRCBackColor(r, c: integer; newColor: TColor);
procedure CloseSimTwo;
function GetRobotVel2D(R: integer): TState2D;
function GetRobotCenterOfMass(R: integer): TPoint3D;
procedure SetSolidPosMat(R, i: integer; P: Matrix);
function GetSolidLinearVelMat(R, i: integer): Matrix;
function GetSolidAgularVelMat(R, i: integer): Matrix;
function GetSolidVx(R, i: integer): double;
function GetSolidVy(R, i: integer): double;
function GetSolidVz(R, i: integer): double;
procedure SetSolidMass(R, i: integer; nmass: double);
function GetSolidMass(R, i: integer): double;
function GetSolidCenterOfMass(R, i: integer): TPoint3D;
function GetSolidTag(R, i: integer): string;
procedure SetSolidTag(R, i: integer; newTag: string);
function GetSolidColor(R, i: integer): TRGBAColor;
procedure SetSolidSurfaceFriction(R, i: integer; mu, mu2: double);
procedure SetSolidForce(R, i: integer; Fx, Fy, Fz: double);
function GetSolidSize(R, i: integer): TPoint3D;
procedure SetSolidSize(R, i: integer; x, y, z: double);
procedure SetFireScale(x, y, z: double);
procedure SetFirePosition(x, y, z: double);
procedure StartFire;
procedure StopFire;
procedure StopSolidFire(R, I: integer);
procedure StartSolidFire(R, I: integer);
procedure SetGlobalSensorVin(i: integer; Vin: byte);
procedure SetSensorColor(R, i: integer; Red, Green, Blue: byte);
procedure SetThingColor(T, c: integer; Red, Green, Blue: byte);
function GetThingRotMat(T: integer): Matrix;
procedure SetThingRotationMat(T: integer; Rot: Matrix);
function GetThingAgularVelMat(T: integer): Matrix;
function GetThingSize(T: integer): TPoint3D;
procedure SetThingSize(T: integer; x, y, z: double);
function AddThingBox(ID: string; mass, posx, posY, posZ, sizeX, sizeY, sizeZ: double; rgb24: integer): integer;
function AddThingSphere(ID: string; mass, posX, posY, posZ, radius: double; rgb24: integer): integer;
function AddThingCylinder(ID: string; mass, posx, posY, posZ, radius, len: double; rgb24: integer): integer;
function DeleteThing(ID: string): integer;
procedure MeshThing(ID, MeshFile, MeshShadowFile: string; MeshScale: double; MeshCastsShadows: boolean);
procedure ClearThings;
procedure SetThingForce(T: integer; Fx, Fy, Fz: double);
procedure SetThingForceAtRelPos(T: integer; Fx, Fy, Fz, Px, Py, Pz: double);
procedure SetThingRelForce(T: integer; Fx, Fy, Fz: double);
procedure SetThingRelForceAtRelPos(T: integer; Fx, Fy, Fz, Px, Py, Pz: double);
procedure SetThingSurfaceMu(T: integer; mu, mu2: double);
function GetThingSpeed(T: integer): TPoint3D;
procedure SetThingSpeed(T: integer; vx, vy, vz: double);
procedure SetThingLinearVel(T: integer; x, y, z: double);
procedure SetThingAngularVel(T: integer; x, y, z: double);
function GetThingAngularVel(T: integer): TPoint3D;
function GetShellPos(R, i: integer): TPoint3D;
procedure SetShellColor(R, i: integer; Red, Green, Blue: byte);
function GetShellColor(R, i: integer): TRGBAColor;
function GetObstacleIndex(ID: string): integer;
procedure SetObstacleColor(I: integer; Red, Green, Blue: byte);
function GetObstacleColor(I: integer): TRGBAColor;
procedure SetObstaclePos(T: integer; x, y, z: double);
function GetObstacleRotMat(T: integer): Matrix;
procedure SetObstacleRotationMat(T: integer; Rot: Matrix);
function DeleteObstacle(ID: string): integer;
function GetAxisUIPower(R, i: integer): double;
function GetAxisTWPower(R, i: integer): double;
function GetAxisStateRef(R, i: integer): TAxisState;
procedure SetAxisStateRef(R, i: integer; aState: TAxisState);
function GetAxisPosRefDeg(R, i: integer): double;
function GetAxisSpeedRefDeg(R, i: integer): double;
function GetAxisMotorSpeed(R, i: integer): double;
function GetAxisMotorPos(R, i: integer): double;
function GetAxisMotorPosDeg(R, i: integer): double;
function GetAxisEnergy(R, i: integer): double;
procedure ResetAxisEnergy(R, i: integer);
procedure SetMotorControllerPars(R, i: integer; nKi, nKd, nKp, nKf: double);
function GetMotorControllerPars(R, i: integer): TMotorControllerPars;
procedure SetMotorControllerMode(R, i: integer; newMode: string);
function GetMotorControllerMode(R, i: integer): string;
procedure SetFrictionDef(R, i: integer; nBv, nFc, nCoulombLimit: double);
function GetFrictionDef(R, i: integer): TFrictionDef;
procedure SetBeltSpeed(R, i: integer; nSpeed: double);
function GetBeltSpeed(R, i: integer): double;
procedure SetAxisSpring(R, i: integer; k, ZeroPos: double);
procedure SetTrailColor(T: integer; Red, Green, Blue: byte);
procedure DelTrailNode(T: integer);
procedure ChartSetAxisMinMax(ChartIndex: integer; Xmin, Xmax, Ymin, Ymax: double);
function ChartSeriesGetCount(ChartIndex: integer): integer;
function ChartSeriesCreate(ChartIndex: integer): integer;
procedure ChartSeriesDeleteAll(ChartIndex: integer);
function ReadUDPPacket: string;
function GetUDPPacketCount: integer;
function getModbusCoil(bit_addr: integer): boolean;
function getModbusInput(bit_addr: integer): boolean;
procedure setModbusCoil(bit_addr: integer; new_state: boolean);
procedure setModbusInput(bit_addr: integer; new_state: boolean);

{ For the other support units: robot R's axis count, axis i's joint ID and which of its axes
  (0, 1 for a Universal joint's second), the script's folder. }
function S2SimAxisCount(R: integer): integer;
function S2SimAxisJoint(R, i: integer; out which: integer): string;
function S2SimScriptFolder: string;
{ For the other support units: host function fn called with the numbers a (any count); the
  numbers the call left (S2SimHostNumbers gives their count and the first). }
function S2SimHostCall(fn: longint; const a: array of double): double;
function S2SimHostNumbers(out first: PDouble): longint;
{ The same with two texts (at most 16 numbers). }
function S2SimHostCallS2(fn: longint; const a: array of double; const s, s2: string): double;
{ A file name as SimTwo's scripts mean it: a relative one in the script's folder (SimTwo works in
  the project's folder). }
function InScriptFolder(const name: string): string;

{ dynmatrixutils' Mload and Msave, a relative file name in the script's folder. }
function Mload(const fname: string): Matrix;
procedure Msave(M: Matrix; const fname: string);

{ Called by the wrapper: the HUD text after each call. }
procedure S2SimPublishHUD;
procedure S2SimTakeUDPData;

type
  { The RTL's Halt would end S2Sim itself, with the script's code and without its outputs.
    This one ends the run through the host instead: the wrapper catches it, the runner writes
    its outputs and names the line. Not an Exception, so a script's `on E: Exception` lets it
    pass. }
  TScriptHalt = class
  public
    Code: longint;
    constructor Create(ACode: longint);
  end;

procedure Halt(ErrorCode: longint); overload;
procedure Halt; overload;

implementation

constructor TScriptHalt.Create(ACode: longint);
begin
  inherited Create;
  Code := ACode;
end;

{ Raised at the call in the script (its return address less one byte), so the host names the
  script's line. }
procedure Halt(ErrorCode: longint);
begin
  raise TScriptHalt.Create(ErrorCode) at CodePointer(PtrUInt(get_caller_addr(get_frame)) - 1),
    get_caller_frame(get_frame);
end;

procedure Halt;
begin
  raise TScriptHalt.Create(0) at CodePointer(PtrUInt(get_caller_addr(get_frame)) - 1),
    get_caller_frame(get_frame);
end;

constructor TStringList.Create;
begin
  inherited Create;
  LineBreak := #13#10;
end;

procedure TStringList.SetTextStr(const Value: string);
var s: string; p: SizeInt;
begin
  BeginUpdate;
  try
    Clear;
    p := 1;
    while GetNextLine(Value, s, p) do Add(s);
  finally
    EndUpdate;
  end;
end;

{ --- the host bridge --- }

procedure HostCheck;
var p: Pointer; n: longint; msg: string;
begin
  n := Host.result(Host.host, 2, p);
  if n > 0 then begin
    SetString(msg, PChar(p), n);
    raise EScriptHostError.Create(msg);
  end;
end;

function HostCall(fn: longint; const a: array of double): double; overload;
var buf: array[0..15] of double; i: integer;
begin
  for i := 0 to High(a) do buf[i] := a[i];
  result := Host.call(Host.host, fn, @buf[0], Length(a), nil, 0, nil, 0);
  HostCheck;
end;

function HostCallS(fn: longint; const a: array of double; const s: string): double;
var buf: array[0..15] of double; i: integer;
begin
  for i := 0 to High(a) do buf[i] := a[i];
  result := Host.call(Host.host, fn, @buf[0], Length(a), PChar(s), Length(s), nil, 0);
  HostCheck;
end;

function HostCallS2(fn: longint; const a: array of double; const s, s2: string): double;
var buf: array[0..15] of double; i: integer;
begin
  for i := 0 to High(a) do buf[i] := a[i];
  result := Host.call(Host.host, fn, @buf[0], Length(a), PChar(s), Length(s), PChar(s2), Length(s2));
  HostCheck;
end;

function HostText: string;
var p: Pointer; n: longint;
begin
  n := Host.result(Host.host, 0, p);
  SetString(result, PChar(p), n);
end;

function HostValues: Matrix;
var p: PDouble; n, rc: longint; i: integer;
begin
  n := Host.result(Host.host, 1, Pointer(p));
  { the call's own result is rows*65536 + cols for matrix results }
  result.rows := n;
  result.cols := 1;
  SetLength(result.data, n);
  for i := 0 to n - 1 do result.data[i] := p[i];
  rc := 0;
  if rc <> 0 then ;
end;

function HostMatrix(fn: longint; const a: array of double): Matrix;
var shape: double;
begin
  shape := HostCall(fn, a);
  result := HostValues;
  result.rows := Round(shape) div 65536;
  result.cols := Round(shape) mod 65536;
end;

function HostPoint(fn: longint; const a: array of double): TPoint3D;
var M: Matrix;
begin
  HostCall(fn, a);
  M := HostValues;
  result.x := M.data[0]; result.y := M.data[1]; result.z := M.data[2];
end;

function CallMatrix(fn: longint; const a: array of double; const M: Matrix): double;
var buf: array of double; i: integer;
begin
  SetLength(buf, Length(a) + 2 + Length(M.data));
  for i := 0 to High(a) do buf[i] := a[i];
  buf[Length(a)] := M.rows;
  buf[Length(a) + 1] := M.cols;
  for i := 0 to High(M.data) do buf[Length(a) + 2 + i] := M.data[i];
  result := Host.call(Host.host, fn, @buf[0], Length(buf), nil, 0, nil, 0);
  HostCheck;
end;

{ --- host functions --- }

procedure WriteLn(S: string); begin HostCallS(hWriteLn, [], S); end;
function KeyPressed(k: integer): Boolean; begin result := HostCall(hKeyPressed, [k]) <> 0; end;
function ScriptPeriod: double; begin result := HostCall(hScriptPeriod, []); end;
function GetSceneConstant(constantName: string; defaultValue: double): double;
begin result := HostCallS(hGetSceneConstant, [defaultValue], constantName); end;

procedure SetRCValue(r, c: integer; s: string); begin HostCallS(hSetRCValue, [r, c], s); end;
function GetRCValue(r, c: integer): double; begin result := HostCall(hGetRCValue, [r, c]); end;
function GetRCText(r, c: integer): string; begin HostCall(hGetRCText, [r, c]); result := HostText; end;
function RCButtonPressed(r, c: integer): boolean; begin result := HostCall(hRCButtonPressed, [r, c]) <> 0; end;
procedure ClearButtons; begin HostCall(hClearButtons, []); end;
procedure RefreshSheets; begin HostCall(hRefreshSheets, []); end;

procedure MatrixToRangeF(r, c: integer; const M: Matrix; FormatString: string);
var i, j: Longword;
begin
  if (M.rows = 0) or (M.cols = 0) then exit;
  for i := 0 to M.rows - 1 do
    for j := 0 to M.cols - 1 do
      SetRCValue(r + integer(i), c + integer(j), Format(FormatString, [M.data[j + i * M.cols]]));
end;

procedure MatrixToRange(r, c: integer; const M: Matrix);
begin
  MatrixToRangeF(r, c, M, '%.7g');
end;

function RangeToMatrix(r, c, rows, cols: integer): Matrix;
var i, j: integer;
begin
  result := Mzeros(rows, cols);
  for i := 0 to rows - 1 do
    for j := 0 to cols - 1 do result.data[j + i * cols] := GetRCValue(r + i, c + j);
end;

function GetRobotIndex(ID: string): integer; begin result := Round(HostCallS(hGetRobotIndex, [], ID)); end;
function GetSolidIndex(R: integer; ID: string): integer; begin result := Round(HostCallS(hGetSolidIndex, [R], ID)); end;
function GetSensorIndex(R: integer; ID: string): integer; begin result := Round(HostCallS(hGetSensorIndex, [R], ID)); end;
function GetAxisIndex(R: integer; ID: string; i: integer): integer; begin result := Round(HostCallS(hGetAxisIndex, [R, i], ID)); end;
function GetGlobalSensorIndex(ID: string): integer; begin result := Round(HostCallS(hGetGlobalSensorIndex, [], ID)); end;
function GetThingIndex(ID: string): integer; begin result := Round(HostCallS(hGetThingIndex, [], ID)); end;
function GetThingsCount: integer; begin result := Round(HostCall(hGetThingsCount, [])); end;

procedure SetAxisVoltageRef(R, i: integer; aVoltage: double); begin HostCall(hSetAxisVoltageRef, [R, i, aVoltage]); end;
procedure SetAxisSpeedRef(R, i: integer; aSpeed: double); begin HostCall(hSetAxisSpeedRef, [R, i, aSpeed]); end;
procedure SetAxisPosRef(R, i: integer; aPos: double); begin HostCall(hSetAxisPosRef, [R, i, aPos]); end;
procedure SetAxisTorqueRef(R, i: integer; aTorque: double); begin HostCall(hSetAxisTorqueRef, [R, i, aTorque]); end;
function GetAxisPosRef(R, i: integer): double; begin result := HostCall(hGetAxisPosRef, [R, i]); end;
function GetAxisSpeedRef(R, i: integer): double; begin result := HostCall(hGetAxisSpeedRef, [R, i]); end;
function GetAxisOdo(R, i: integer): integer; begin result := Round(HostCall(hGetAxisOdo, [R, i])); end;
function GetAxisPos(R, i: integer): double; begin result := HostCall(hGetAxisPos, [R, i]); end;
function GetAxisPosDeg(R, i: integer): double; begin result := Deg(GetAxisPos(R, i)); end;
function GetAxisSpeed(R, i: integer): double; begin result := HostCall(hGetAxisSpeed, [R, i]); end;
function GetAxisSpeedDeg(R, i: integer): double; begin result := Deg(GetAxisSpeed(R, i)); end;
function GetAxisI(R, i: integer): double; begin result := HostCall(hGetAxisI, [R, i]); end;
function GetAxisU(R, i: integer): double; begin result := HostCall(hGetAxisU, [R, i]); end;
function GetAxisTorque(R, i: integer): double; begin result := HostCall(hGetAxisTorque, [R, i]); end;
function GetAxisState(R, i: integer): TAxisState;
begin
  result.pos := GetAxisPos(R, i); result.vel := GetAxisSpeed(R, i);
  result.Torque := GetAxisTorque(R, i); result.Vm := GetAxisU(R, i); result.Im := GetAxisI(R, i);
end;
procedure SetMotorActive(R, i: integer; nState: boolean); begin HostCall(hSetMotorActive, [R, i, Ord(nState)]); end;
function IsMotorActive(R, i: integer): boolean; begin result := HostCall(hIsMotorActive, [R, i]) <> 0; end;
procedure SetMotorControllerState(R, i: integer; newState: boolean); begin HostCall(hSetMotorControllerState, [R, i, Ord(newState)]); end;
function GetMotorControllerState(R, i: integer): boolean; begin result := HostCall(hGetMotorControllerState, [R, i]) <> 0; end;
function GetMotorPars(R, i: integer): TMotorPars;
var M: Matrix;
begin
  HostCall(hGetMotorPars, [R, i]);
  M := HostValues;
  result.Ri := M.data[0]; result.Li := M.data[1]; result.Ki := M.data[2]; result.Vmax := M.data[3];
  result.Imax := M.data[4]; result.GearRatio := M.data[5]; result.simple := M.data[6] <> 0;
  result.active := M.data[7] <> 0;
end;
procedure SetMotorPars(R, i: integer; aMotorPars: TMotorPars);
begin
  with aMotorPars do
    HostCall(hSetMotorPars, [R, i, Ri, Li, Ki, Vmax, Imax, GearRatio, Ord(simple), Ord(active)]);
end;

function GetSensorVal(R, i: integer): double; begin result := HostCall(hGetSensorVal, [R, i]); end;
function GetSensorValues(R, i: integer): Matrix; begin result := HostMatrix(hGetSensorValues, [R, i]); end;
procedure SetSensorVin(R, i: integer; Vin: byte); begin HostCall(hSetSensorVin, [R, i, Vin]); end;
function GetGlobalSensorVal(i: integer): double; begin result := HostCall(hGetGlobalSensorVal, [i]); end;
function GetGlobalSensorValues(i: integer): Matrix; begin result := HostMatrix(hGetGlobalSensorValues, [i]); end;

procedure SetRobotPos(R: integer; x, y, z, teta: double); begin HostCall(hSetRobotPos, [R, x, y, z, teta]); end;
function GetRobotX(R: integer): double; begin result := HostCall(hGetRobotX, [R]); end;
function GetRobotY(R: integer): double; begin result := HostCall(hGetRobotY, [R]); end;
function GetRobotTheta(R: integer): double; begin result := HostCall(hGetRobotTheta, [R]); end;
function GetRobotVx(R: integer): double; begin result := HostCall(hGetRobotVx, [R]); end;
function GetRobotVy(R: integer): double; begin result := HostCall(hGetRobotVy, [R]); end;
function GetRobotW(R: integer): double; begin result := HostCall(hGetRobotW, [R]); end;
function GetRobotPos2D(R: integer): TState2D;
begin result.x := GetRobotX(R); result.y := GetRobotY(R); result.angle := GetRobotTheta(R); end;
function GetSolidPos(R, i: integer): TPoint3D; begin result := HostPoint(hGetSolidPos, [R, i]); end;
function GetSolidX(R, i: integer): double; begin result := GetSolidPos(R, i).x; end;
function GetSolidY(R, i: integer): double; begin result := GetSolidPos(R, i).y; end;
function GetSolidZ(R, i: integer): double; begin result := GetSolidPos(R, i).z; end;
function GetSolidTheta(R, i: integer): double; begin result := HostCall(hGetSolidTheta, [R, i]); end;
function GetSolidPosMat(R, i: integer): Matrix;
var p: TPoint3D;
begin
  if R < 0 then raise Exception.Create(SysUtils.Format('Invalid Robot Index: %d', [R]));
  p := GetSolidPos(R, i);
  result := Mzeros(3, 1);
  result.data[0] := p.x; result.data[1] := p.y; result.data[2] := p.z;
end;
function GetSolidRotMat(R, i: integer): Matrix; begin result := HostMatrix(hGetSolidRotMat, [R, i]); end;
function GetSolidLinearVel(R, i: integer): TPoint3D; begin result := HostPoint(hGetSolidLinearVel, [R, i]); end;
procedure SetSolidPos(R, i: integer; x, y, z: double); begin HostCall(hSetSolidPos, [R, i, x, y, z]); end;
procedure SetSolidRotationMat(R, i: integer; Rot: Matrix); begin CallMatrix(hSetSolidRotationMat, [R, i], Rot); end;
procedure SetSolidLinearVel(R, i: integer; x, y, z: double); begin HostCall(hSetSolidLinearVel, [R, i, x, y, z]); end;
procedure SetSolidAngularVel(R, i: integer; x, y, z: double); begin HostCall(hSetSolidAngularVel, [R, i, x, y, z]); end;
procedure SetSolidColor(R, I: integer; Red, Green, Blue: byte); begin HostCall(hSetSolidColor, [R, I, Red, Green, Blue]); end;
procedure SetShellTag(R, i: integer; newTag: string); begin HostCallS(hSetShellTag, [R, i], newTag); end;
function GetShellTag(R, i: integer): string; begin HostCall(hGetShellTag, [R, i]); result := HostText; end;

procedure SetThingPos(T: integer; x, y, z: double); begin HostCall(hSetThingPos, [T, x, y, z]); end;
function GetThingPos(T: integer): TPoint3D; begin result := HostPoint(hGetThingPos, [T]); end;
function GetThingColor(T, c: integer): TRGBAColor;
var M: Matrix;
begin
  HostCall(hGetThingColor, [T, c]);
  M := HostValues;
  result.Red := Round(M.data[0]); result.Green := Round(M.data[1]);
  result.Blue := Round(M.data[2]); result.alpha := Round(M.data[3]);
end;
function GetObstaclePos(T: integer): TPoint3D; begin result := HostPoint(hGetObstaclePos, [T]); end;
function AddOBstacleBox(ID: string; posx, posY, posZ, sizeX, sizeY, sizeZ: double; rgb24: integer): integer;
begin result := Round(HostCallS(hAddOBstacleBox, [posx, posY, posZ, sizeX, sizeY, sizeZ, rgb24], ID)); end;
procedure ClearObstacles; begin HostCall(hClearObstacles, []); end;

procedure ChartSeriesSetCount(ChartIndex, SeriesCount: integer); begin HostCall(hChartSeriesSetCount, [ChartIndex, SeriesCount]); end;
procedure ChartSeriesSetColor(ChartIndex, SeriesIndex: integer; newColor: TColor); begin HostCall(hChartSeriesSetColor, [ChartIndex, SeriesIndex, newColor]); end;
procedure ChartSeriesClear(ChartIndex, SeriesIndex: integer); begin HostCall(hChartSeriesClear, [ChartIndex, SeriesIndex]); end;
procedure ChartSeriesAddXY(ChartIndex, SeriesIndex: integer; X, Y: double); begin HostCall(hChartSeriesAddXY, [ChartIndex, SeriesIndex, X, Y]); end;

procedure AddTrailNode(T: integer; x, y, z: double); begin HostCall(hAddTrailNode, [T, x, y, z]); end;
procedure ClearTrail(T: integer); begin HostCall(hClearTrail, [T]); end;

procedure WriteUDPData(ToIP: string; ToPort: integer; s: string); begin HostCallS2(hWriteUDPData, [ToPort], ToIP, s); end;
{ SimTwo appends what arrives to UDPDataRead where it stands, and ReadUDPData takes it all:
  one stream, whatever the script does to it between the two. }
procedure S2SimTakeUDPData;
var s: string;
begin
  HostCall(hUDPDataArrived, []);
  s := HostText;
  if s <> '' then UDPDataRead.WriteBuffer(s[1], Length(s));
end;
function ReadUDPData: string;
begin
  S2SimTakeUDPData;
  SetLength(result, UDPDataRead.Size);
  UDPDataRead.Position := 0;
  if UDPDataRead.Size > 0 then UDPDataRead.ReadBuffer(result[1], UDPDataRead.Size);
  UDPDataRead.Clear;
end;
procedure WriteComPort(s: string); begin HostCallS(hWriteComPort, [], s); end;
function ReadComPort: string; begin HostCall(hReadComPort, []); result := HostText; end;

{ --- what S2Sim does not have (yet): a named error, never a silent no-op --- }

function RGBToColor(R, G, B: Byte): TColor; begin result := R or (G shl 8) or (B shl 16); end;
procedure SetRCBackColor(r, c: integer; newColor: TColor); begin HostCall(hSetRCBackColor, [r, c, newColor]); end;
procedure CloseSimTwo; begin HostCall(hCloseSimTwo, []); end;

function GetRobotVel2D(R: integer): TState2D;
begin result.x := GetRobotVx(R); result.y := GetRobotVy(R); result.angle := GetRobotW(R); end;
function GetRobotCenterOfMass(R: integer): TPoint3D; begin result := HostPoint(hGetRobotCenterOfMass, [R]); end;
procedure SetSolidPosMat(R, i: integer; P: Matrix);
begin SetSolidPos(R, i, Mgetv(P, 0, 0), Mgetv(P, 1, 0), Mgetv(P, 2, 0)); end;
function PointColumn(const p: TPoint3D): Matrix;
begin
  result := Mzeros(3, 1);
  result.data[0] := p.x; result.data[1] := p.y; result.data[2] := p.z;
end;
function GetSolidLinearVelMat(R, i: integer): Matrix; begin result := PointColumn(GetSolidLinearVel(R, i)); end;
function GetSolidAgularVelMat(R, i: integer): Matrix; begin result := PointColumn(HostPoint(hGetSolidAngularVel, [R, i])); end;
function GetSolidVx(R, i: integer): double; begin result := GetSolidLinearVel(R, i).x; end;
function GetSolidVy(R, i: integer): double; begin result := GetSolidLinearVel(R, i).y; end;
function GetSolidVz(R, i: integer): double; begin result := GetSolidLinearVel(R, i).z; end;
procedure SetSolidMass(R, i: integer; nmass: double); begin HostCall(hSetSolidMass, [R, i, nmass]); end;
function GetSolidMass(R, i: integer): double; begin result := HostCall(hGetSolidMass, [R, i]); end;
function GetSolidCenterOfMass(R, i: integer): TPoint3D; begin result := HostPoint(hGetSolidCenterOfMass, [R, i]); end;
function GetSolidTag(R, i: integer): string; begin HostCall(hGetSolidTag, [R, i]); result := HostText; end;
procedure SetSolidTag(R, i: integer; newTag: string); begin HostCallS(hSetSolidTag, [R, i], newTag); end;
function GetSolidColor(R, i: integer): TRGBAColor;
var M: Matrix;
begin
  HostCall(hGetSolidColor, [R, i]);
  M := HostValues;
  result.Red := Round(M.data[0]); result.Green := Round(M.data[1]);
  result.Blue := Round(M.data[2]); result.alpha := Round(M.data[3]);
end;
procedure SetSolidSurfaceFriction(R, i: integer; mu, mu2: double); begin HostCall(hSetSolidSurfaceFriction, [R, i, mu, mu2]); end;
procedure SetSolidForce(R, i: integer; Fx, Fy, Fz: double); begin HostCall(hSetSolidForce, [R, i, Fx, Fy, Fz]); end;
function GetSolidSize(R, i: integer): TPoint3D; begin result := HostPoint(hGetSolidSize, [R, i]); end;
procedure SetSolidSize(R, i: integer; x, y, z: double); begin HostCall(hSetSolidSize, [R, i, x, y, z]); end;


procedure SetFireScale(x, y, z: double); begin HostCall(hFire, [0, x, y, z]); end;
procedure SetFirePosition(x, y, z: double); begin HostCall(hFire, [1, x, y, z]); end;
procedure StartFire; begin HostCall(hFire, [2]); end;
procedure StopFire; begin HostCall(hFire, [3]); end;
procedure StopSolidFire(R, I: integer); begin HostCall(hFire, [5, R, I]); end;
procedure StartSolidFire(R, I: integer); begin HostCall(hFire, [4, R, I]); end;

procedure SetGlobalSensorVin(i: integer; Vin: byte); begin HostCall(hSetGlobalSensorVin, [i, Vin]); end;
procedure SetSensorColor(R, i: integer; Red, Green, Blue: byte); begin HostCall(hSetSensorColor, [R, i, Red, Green, Blue]); end;

procedure SetThingColor(T, c: integer; Red, Green, Blue: byte); begin HostCall(hSetThingColor, [T, c, Red, Green, Blue]); end;
function GetThingRotMat(T: integer): Matrix; begin result := HostMatrix(hGetThingRotMat, [T]); end;
procedure SetThingRotationMat(T: integer; Rot: Matrix); begin CallMatrix(hSetThingRotationMat, [T], Rot); end;
function GetThingAgularVelMat(T: integer): Matrix; begin result := PointColumn(GetThingAngularVel(T)); end;
function GetThingSize(T: integer): TPoint3D; begin result := HostPoint(hGetThingSize, [T]); end;
procedure SetThingSize(T: integer; x, y, z: double); begin HostCall(hSetThingSize, [T, x, y, z]); end;
function AddThingBox(ID: string; mass, posx, posY, posZ, sizeX, sizeY, sizeZ: double; rgb24: integer): integer;
begin result := Round(HostCallS(hAddThingBox, [mass, posx, posY, posZ, sizeX, sizeY, sizeZ, rgb24], ID)); end;
function AddThingSphere(ID: string; mass, posX, posY, posZ, radius: double; rgb24: integer): integer;
begin result := Round(HostCallS(hAddThingSphere, [mass, posX, posY, posZ, radius, rgb24], ID)); end;
function AddThingCylinder(ID: string; mass, posx, posY, posZ, radius, len: double; rgb24: integer): integer;
begin result := Round(HostCallS(hAddThingCylinder, [mass, posx, posY, posZ, radius, len, rgb24], ID)); end;
function DeleteThing(ID: string): integer; begin result := Round(HostCallS(hDeleteThing, [], ID)); end;
procedure ClearThings; begin HostCall(hClearThings, []); end;
procedure SetThingForce(T: integer; Fx, Fy, Fz: double); begin HostCall(hSetThingForce, [T, Fx, Fy, Fz]); end;
procedure SetThingForceAtRelPos(T: integer; Fx, Fy, Fz, Px, Py, Pz: double);
begin HostCall(hSetThingForceAtRelPos, [T, Fx, Fy, Fz, Px, Py, Pz]); end;
procedure SetThingRelForce(T: integer; Fx, Fy, Fz: double); begin HostCall(hSetThingRelForce, [T, Fx, Fy, Fz]); end;
procedure SetThingRelForceAtRelPos(T: integer; Fx, Fy, Fz, Px, Py, Pz: double);
begin HostCall(hSetThingRelForceAtRelPos, [T, Fx, Fy, Fz, Px, Py, Pz]); end;
procedure SetThingSurfaceMu(T: integer; mu, mu2: double); begin HostCall(hSetThingSurfaceMu, [T, mu, mu2]); end;
function GetThingSpeed(T: integer): TPoint3D; begin result := HostPoint(hGetThingSpeed, [T]); end;
procedure SetThingSpeed(T: integer; vx, vy, vz: double); begin HostCall(hSetThingSpeed, [T, vx, vy, vz]); end;
procedure SetThingLinearVel(T: integer; x, y, z: double); begin HostCall(hSetThingLinearVel, [T, x, y, z]); end;
procedure SetThingAngularVel(T: integer; x, y, z: double); begin HostCall(hSetThingAngularVel, [T, x, y, z]); end;
function GetThingAngularVel(T: integer): TPoint3D; begin result := HostPoint(hGetThingAngularVel, [T]); end;

function GetShellPos(R, i: integer): TPoint3D; begin result := HostPoint(hGetShellPos, [R, i]); end;
procedure SetShellColor(R, i: integer; Red, Green, Blue: byte); begin HostCall(hSetShellColor, [R, i, Red, Green, Blue]); end;
function GetShellColor(R, i: integer): TRGBAColor;
var M: Matrix;
begin
  HostCall(hGetShellColor, [R, i]);
  M := HostValues;
  result.Red := Round(M.data[0]); result.Green := Round(M.data[1]);
  result.Blue := Round(M.data[2]); result.alpha := Round(M.data[3]);
end;

function GetObstacleIndex(ID: string): integer; begin result := Round(HostCallS(hGetObstacleIndex, [], ID)); end;
procedure SetObstacleColor(I: integer; Red, Green, Blue: byte); begin HostCall(hSetObstacleColor, [I, Red, Green, Blue]); end;
function GetObstacleColor(I: integer): TRGBAColor;
var M: Matrix;
begin
  HostCall(hGetObstacleColor, [I]);
  M := HostValues;
  result.Red := Round(M.data[0]); result.Green := Round(M.data[1]);
  result.Blue := Round(M.data[2]); result.alpha := Round(M.data[3]);
end;
procedure SetObstaclePos(T: integer; x, y, z: double); begin HostCall(hSetObstaclePos, [T, x, y, z]); end;
function GetObstacleRotMat(T: integer): Matrix; begin result := HostMatrix(hGetObstacleRotMat, [T]); end;
procedure SetObstacleRotationMat(T: integer; Rot: Matrix); begin CallMatrix(hSetObstacleRotationMat, [T], Rot); end;
function DeleteObstacle(ID: string): integer; begin result := Round(HostCallS(hDeleteObstacle, [], ID)); end;

function GetAxisUIPower(R, i: integer): double; begin result := HostCall(hGetAxisUIPower, [R, i]); end;
function GetAxisTWPower(R, i: integer): double; begin result := GetAxisTorque(R, i) * GetAxisSpeed(R, i); end;
function GetAxisStateRef(R, i: integer): TAxisState;
begin
  result.pos := GetAxisPosRef(R, i); result.vel := GetAxisSpeedRef(R, i);
  result.Torque := 0; result.Vm := 0; result.Im := 0;
end;
procedure SetAxisStateRef(R, i: integer; aState: TAxisState);
begin SetAxisPosRef(R, i, aState.pos); SetAxisSpeedRef(R, i, aState.vel); end;
function GetAxisPosRefDeg(R, i: integer): double; begin result := Deg(GetAxisPosRef(R, i)); end;
function GetAxisSpeedRefDeg(R, i: integer): double; begin result := Deg(GetAxisSpeedRef(R, i)); end;
function GetAxisMotorSpeed(R, i: integer): double; begin result := GetAxisSpeed(R, i); end;
function GetAxisMotorPos(R, i: integer): double; begin result := GetAxisPos(R, i); end;
function GetAxisMotorPosDeg(R, i: integer): double; begin result := Deg(GetAxisPos(R, i)); end;
function GetAxisEnergy(R, i: integer): double; begin result := HostCall(hGetAxisEnergy, [R, i]); end;
procedure ResetAxisEnergy(R, i: integer); begin HostCall(hResetAxisEnergy, [R, i]); end;
procedure SetMotorControllerPars(R, i: integer; nKi, nKd, nKp, nKf: double);
begin HostCall(hSetMotorControllerPars, [R, i, nKi, nKd, nKp, nKf]); end;
function GetMotorControllerPars(R, i: integer): TMotorControllerPars;
var M: Matrix;
begin
  HostCall(hGetMotorControllerPars, [R, i]);
  M := HostValues;
  result.Ki := M.data[0]; result.Kd := M.data[1]; result.Kp := M.data[2]; result.Kf := M.data[3];
end;
procedure SetMotorControllerMode(R, i: integer; newMode: string); begin HostCallS(hSetMotorControllerMode, [R, i], newMode); end;
function GetMotorControllerMode(R, i: integer): string; begin HostCall(hGetMotorControllerMode, [R, i]); result := HostText; end;
procedure SetFrictionDef(R, i: integer; nBv, nFc, nCoulombLimit: double);
begin HostCall(hSetFrictionDef, [R, i, nBv, nFc, nCoulombLimit]); end;
function GetFrictionDef(R, i: integer): TFrictionDef;
var M: Matrix;
begin
  HostCall(hGetFrictionDef, [R, i]);
  M := HostValues;
  result.Bv := M.data[0]; result.Fc := M.data[1]; result.CoulombLimit := M.data[2];
end;
procedure SetBeltSpeed(R, i: integer; nSpeed: double); begin HostCall(hSetBeltSpeed, [R, i, nSpeed]); end;
function GetBeltSpeed(R, i: integer): double; begin result := HostCall(hGetBeltSpeed, [R, i]); end;
procedure SetAxisSpring(R, i: integer; k, ZeroPos: double); begin HostCall(hSetAxisSpring, [R, i, k, ZeroPos]); end;


procedure SetTrailColor(T: integer; Red, Green, Blue: byte); begin HostCall(hSetTrailColor, [T, Red, Green, Blue]); end;
procedure DelTrailNode(T: integer); begin HostCall(hDelTrailNode, [T]); end;
procedure ChartSetAxisMinMax(ChartIndex: integer; Xmin, Xmax, Ymin, Ymax: double);
begin HostCall(hChartSetAxisMinMax, [ChartIndex, Xmin, Xmax, Ymin, Ymax]); end;
function ChartSeriesGetCount(ChartIndex: integer): integer; begin result := Round(HostCall(hChartSeriesGetCount, [ChartIndex])); end;
function ChartSeriesCreate(ChartIndex: integer): integer; begin result := Round(HostCall(hChartSeriesCreate, [ChartIndex])); end;
procedure ChartSeriesDeleteAll(ChartIndex: integer); begin HostCall(hChartSeriesDeleteAll, [ChartIndex]); end;
function ReadUDPPacket: string; begin HostCall(hReadUDPPacket, []); result := HostText; end;
function GetUDPPacketCount: integer; begin result := Round(HostCall(hGetUDPPacketCount, [])); end;
function getModbusCoil(bit_addr: integer): boolean; begin result := HostCall(hgetModbusCoil, [bit_addr]) <> 0; end;
function getModbusInput(bit_addr: integer): boolean; begin result := HostCall(hgetModbusInput, [bit_addr]) <> 0; end;
procedure setModbusCoil(bit_addr: integer; new_state: boolean); begin HostCall(hsetModbusCoil, [bit_addr, Ord(new_state)]); end;
procedure setModbusInput(bit_addr: integer; new_state: boolean); begin HostCall(hsetModbusInput, [bit_addr, Ord(new_state)]); end;

function S2SimAxisCount(R: integer): integer; begin result := Round(HostCall(hAxisCount, [R])); end;
function S2SimAxisJoint(R, i: integer; out which: integer): string;
begin
  which := Round(HostCall(hAxisJoint, [R, i]));
  result := HostText;
end;
function S2SimScriptFolder: string; begin HostCall(hScriptFolder, []); result := HostText; end;
function S2SimHostCall(fn: longint; const a: array of double): double;
var zero: double;
begin
  zero := 0;
  if Length(a) = 0 then result := Host.call(Host.host, fn, @zero, 0, nil, 0, nil, 0)
  else result := Host.call(Host.host, fn, @a[0], Length(a), nil, 0, nil, 0);
  HostCheck;
end;
function S2SimHostCallS2(fn: longint; const a: array of double; const s, s2: string): double;
begin
  result := HostCallS2(fn, a, s, s2);
end;
function S2SimHostNumbers(out first: PDouble): longint;
begin
  result := Host.result(Host.host, 1, Pointer(first));
end;
function InScriptFolder(const name: string): string;
begin
  if (name <> '') and (name[1] = '/') then result := name
  else result := IncludeTrailingPathDelimiter(S2SimScriptFolder) + name;
end;
function Mload(const fname: string): Matrix; begin result := s2simtwo_matrix.Mload(InScriptFolder(fname)); end;
procedure Msave(M: Matrix; const fname: string); begin s2simtwo_matrix.Msave(M, InScriptFolder(fname)); end;

procedure MeshThing(ID, MeshFile, MeshShadowFile: string; MeshScale: double; MeshCastsShadows: boolean);
var mesh, shadow: string;
begin
  mesh := ''; shadow := '';
  if MeshFile <> '' then mesh := InScriptFolder(MeshFile);
  if MeshShadowFile <> '' then shadow := InScriptFolder(MeshShadowFile);
  HostCallS2(hMeshThing, [MeshScale, Ord(MeshCastsShadows)], ID, mesh + #0 + shadow);
end;

procedure S2SimPublishHUD;
begin
  HostCallS(hHUDText, [], HUDStrings.Text);
end;

initialization
  DefaultFormatSettings.DecimalSeparator := '.';
  HUDStrings := TStringList.Create;
  UDPDataRead := TMemoryStream.Create;
finalization
  UDPDataRead.Free;
  HUDStrings.Free;
end.
