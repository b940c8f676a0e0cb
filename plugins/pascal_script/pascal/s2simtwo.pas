{ S2Sim's SimTwo script support unit (written for S2Sim; no SimTwo source). It gives a SimTwo
  `control.pas`, compiled unchanged with Free Pascal -Mdelphi, what SimTwo's Pascal Script
  engine gives it: SimTwo's types and constants, its pure helpers with SimTwo's definitions,
  the Matrix API, and the host functions, each forwarding to the C++ host through one table
  filled at load (plugins/pascal_script/host_api.cpp). It comes last in the wrapper's `uses`,
  so its WriteLn, Sqr, Sign, Format, TStringList... shadow the RTL's (docs/scripting.md). }
unit s2simtwo;

{$mode delphi}{$H+}

interface

uses SysUtils, Classes, Math, Types, s2simtwo_matrix, s2simtwo_helpers;

{S2SIM_HOST_IDS}

const
  MaxDim = 8;
  k = MaxDim - 1;

  VK_LBUTTON = 1; VK_RBUTTON = 2; VK_CANCEL = 3; VK_MBUTTON = 4; VK_BACK = 8; VK_TAB = 9;
  VK_CLEAR = 12; VK_RETURN = 13; VK_SHIFT = 16; VK_CONTROL = 17; VK_MENU = 18; VK_PAUSE = 19;
  VK_CAPITAL = 20; VK_KANA = 21; VK_HANGUL = 21; VK_JUNJA = 23; VK_FINAL = 24; VK_HANJA = 25;
  VK_KANJI = 25; VK_ESCAPE = 27; VK_CONVERT = 28; VK_NONCONVERT = 29; VK_ACCEPT = 30;
  VK_MODECHANGE = 31; VK_SPACE = 32; VK_PRIOR = 33; VK_NEXT = 34; VK_END = 35; VK_HOME = 36;
  VK_LEFT = 37; VK_UP = 38; VK_RIGHT = 39; VK_DOWN = 40; VK_SELECT = 41; VK_PRINT = 42;
  VK_EXECUTE = 43; VK_SNAPSHOT = 44; VK_INSERT = 45; VK_DELETE = 46; VK_HELP = 47;
  VK_LWIN = 91; VK_RWIN = 92; VK_APPS = 93;
  VK_NUMPAD0 = 96; VK_NUMPAD1 = 97; VK_NUMPAD2 = 98; VK_NUMPAD3 = 99; VK_NUMPAD4 = 100;
  VK_NUMPAD5 = 101; VK_NUMPAD6 = 102; VK_NUMPAD7 = 103; VK_NUMPAD8 = 104; VK_NUMPAD9 = 105;
  VK_MULTIPLY = 106; VK_ADD = 107; VK_SEPARATOR = 108; VK_SUBTRACT = 109; VK_DECIMAL = 110;
  VK_DIVIDE = 111; VK_F1 = 112; VK_F2 = 113; VK_F3 = 114; VK_F4 = 115; VK_F5 = 116;
  VK_F6 = 117; VK_F7 = 118; VK_F8 = 119; VK_F9 = 120; VK_F10 = 121; VK_F11 = 122; VK_F12 = 123;
  VK_F13 = 124; VK_F14 = 125; VK_F15 = 126; VK_F16 = 127; VK_F17 = 128; VK_F18 = 129;
  VK_F19 = 130; VK_F20 = 131; VK_F21 = 132; VK_F22 = 133; VK_F23 = 134; VK_F24 = 135;
  VK_NUMLOCK = 144; VK_SCROLL = 145; VK_LSHIFT = 160; VK_RSHIFT = 161; VK_LCONTROL = 162;
  VK_RCONTROL = 163; VK_LMENU = 164; VK_RMENU = 165; VK_PROCESSKEY = 229; VK_ATTN = 246;
  VK_CRSEL = 247; VK_EXSEL = 248; VK_EREOF = 249; VK_PLAY = 250; VK_ZOOM = 251;
  VK_NONAME = 252; VK_PA1 = 253; VK_OEM_CLEAR = 254;

type
  TColor = longint;

const
  clBlack = TColor($000000); clMaroon = TColor($000080); clGreen = TColor($008000);
  clOlive = TColor($008080); clNavy = TColor($800000); clPurple = TColor($800080);
  clTeal = TColor($808000); clGray = TColor($808080); clSilver = TColor($C0C0C0);
  clRed = TColor($0000FF); clLime = TColor($00FF00); clYellow = TColor($00FFFF);
  clBlue = TColor($FF0000); clFuchsia = TColor($FF00FF); clAqua = TColor($FFFF00);
  clLtGray = TColor($C0C0C0); clDkGray = TColor($808080); clWhite = TColor($FFFFFF);
  clNone = TColor($1FFFFFFF); clDefault = TColor($20000000);

type
  TPoint3D = record x, y, z: double; end;
  TState2D = record x, y, angle: double; end;
  TAxisState = record pos, vel, Torque, Vm, Im: double; end;
  TAxisPoint = record pos, speed, final_time: double; end;
  TSpringDef = record K, ZeroPos: double; end;
  TMotorPars = record Ri, Li, Ki, Vmax, Imax, GearRatio: double; simple, active: boolean; end;
  TMotorControllerPars = record Ki, Kd, Kp, Kf: double; end;
  TFrictionDef = record Bv, Fc, CoulombLimit: double; end;
  TRGBAColor = record Red, Green, Blue, alpha: integer; end;
  TExtents = record Min, Max: TPoint3D; end;

  { Rendering's types (canvas, camera, spray paint): declared so that scripts compile; every
    routine that would draw or read pixels raises "... belongs to rendering". }
  TPaintVisuals = integer;
  THistogram = array of double;
  TTriangle = record v1, v2, v3: TPoint3D; end;
  TTriangles = array of TTriangle;
  TCanvasTool = class
  public
    Color: TColor;
    Width: integer;
    Size: integer;
    Name: string;
  end;
  TCanvas = class
  public
    Brush, Pen, Font: TCanvasTool;
    procedure TextOut(X, Y: integer; const Text: string);
    procedure FillRect(const R: TRect);
    procedure Rectangle(X1, Y1, X2, Y2: integer);
    procedure Ellipse(X1, Y1, X2, Y2: integer);
    procedure MoveTo(X, Y: integer);
    procedure LineTo(X, Y: integer);
  end;
  TBitmap = class
  public
    Canvas: TCanvas;
    Width, Height: integer;
  end;

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

  EScriptHostError = class(Exception);

var
  Time: double;
  HUDStrings: TStringList;
  UDPDataRead: TMemoryStream;  { declared; S2Sim does not fill it (docs/scripting.md) }
  CamBitmap: TBitmap;          { rendering: its canvas raises }
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
function GetSolidCanvas(R, i: integer): TCanvas;
function GetObstacleCanvas(i: integer): TCanvas;
procedure SolidCanvasClear(R, i: integer);
function GetPaintGunMinDist(i: integer): double;
function GetPaintTargetExtents(i: integer): TExtents;
procedure ResetPaintTargetPaint(i: integer);
procedure SetPaintTargetPaintMode(i: integer; paintMode: TPaintVisuals);
procedure SetSprayGunOn(i: integer);
procedure SetSprayGunOff(i: integer);
function CalculateSprayThicknessHistogram(i: integer; numberOfBins: integer): THistogram;
function CalculateAvgSprayThickness(i: integer): double;
function CalculateSDSprayThickness(i: integer): double;
function CalculatePosAvgSprayThickness(i: integer): double;
function CalculatePosSDSprayThickness(i: integer): double;
function CalculatePosMinSprayThickness(i: integer): double;
function CalculateMinSprayThickness(i: integer): double;
function CalculateMaxSprayThickness(i: integer): double;
function CalculateSprayCoverage(i: integer): double;
function GetPaintTargetTriangles(i: integer): TTriangles;
procedure SetResultTrianglesColor(i: integer; colors: array of TPoint3D);
function GetCameraPixel(X, Y: integer): TRGBAColor;
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
function GetAxisTrajPoint(R, i, idx: integer): TAxisPoint;
procedure SetAxisTrajPoint(R, i, idx: integer; LP: TAxisPoint);
procedure AddAxisTrajPoint(R, i: integer; LP: TAxisPoint);
procedure DelAxisTrajPoint(R, i, idx: integer);
function CountAxisTrajPoints(R, i: integer): integer;
procedure ClearAxisTrajPoints(R, i: integer);
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

{ Called by the wrapper: the HUD text after each call. }
procedure S2SimPublishHUD;

implementation

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
function ReadUDPData: string; begin HostCall(hReadUDPData, []); result := HostText; end;
procedure WriteComPort(s: string); begin HostCallS(hWriteComPort, [], s); end;
function ReadComPort: string; begin HostCall(hReadComPort, []); result := HostText; end;

{ --- what S2Sim does not have (yet): a named error, never a silent no-op --- }

procedure NotYetAvailable(const routine: string);
begin
  raise EScriptHostError.Create(routine + ' is not yet available in S2Sim (docs/scripting.md)');
end;

procedure BelongsToRendering(const routine: string);
begin
  raise EScriptHostError.Create(routine + ' belongs to rendering, which S2Sim does not have yet');
end;

procedure TCanvas.TextOut(X, Y: integer; const Text: string); begin BelongsToRendering('TCanvas.TextOut'); end;
procedure TCanvas.FillRect(const R: TRect); begin BelongsToRendering('TCanvas.FillRect'); end;
procedure TCanvas.Rectangle(X1, Y1, X2, Y2: integer); begin BelongsToRendering('TCanvas.Rectangle'); end;
procedure TCanvas.Ellipse(X1, Y1, X2, Y2: integer); begin BelongsToRendering('TCanvas.Ellipse'); end;
procedure TCanvas.MoveTo(X, Y: integer); begin BelongsToRendering('TCanvas.MoveTo'); end;
procedure TCanvas.LineTo(X, Y: integer); begin BelongsToRendering('TCanvas.LineTo'); end;

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
procedure SetSolidMass(R, i: integer; nmass: double); begin NotYetAvailable('SetSolidMass'); end;
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
procedure SetSolidSurfaceFriction(R, i: integer; mu, mu2: double); begin NotYetAvailable('SetSolidSurfaceFriction'); end;
procedure SetSolidForce(R, i: integer; Fx, Fy, Fz: double); begin HostCall(hSetSolidForce, [R, i, Fx, Fy, Fz]); end;
function GetSolidSize(R, i: integer): TPoint3D; begin result := HostPoint(hGetSolidSize, [R, i]); end;
procedure SetSolidSize(R, i: integer; x, y, z: double); begin NotYetAvailable('SetSolidSize'); end;

function GetSolidCanvas(R, i: integer): TCanvas; begin BelongsToRendering('GetSolidCanvas'); result := nil; end;
function GetObstacleCanvas(i: integer): TCanvas; begin BelongsToRendering('GetObstacleCanvas'); result := nil; end;
procedure SolidCanvasClear(R, i: integer); begin BelongsToRendering('SolidCanvasClear'); end;
function GetPaintGunMinDist(i: integer): double; begin BelongsToRendering('GetPaintGunMinDist'); end;
function GetPaintTargetExtents(i: integer): TExtents; begin BelongsToRendering('GetPaintTargetExtents'); end;
procedure ResetPaintTargetPaint(i: integer); begin BelongsToRendering('ResetPaintTargetPaint'); end;
procedure SetPaintTargetPaintMode(i: integer; paintMode: TPaintVisuals); begin BelongsToRendering('SetPaintTargetPaintMode'); end;
procedure SetSprayGunOn(i: integer); begin BelongsToRendering('SetSprayGunOn'); end;
procedure SetSprayGunOff(i: integer); begin BelongsToRendering('SetSprayGunOff'); end;
function CalculateSprayThicknessHistogram(i: integer; numberOfBins: integer): THistogram;
begin BelongsToRendering('CalculateSprayThicknessHistogram'); end;
function CalculateAvgSprayThickness(i: integer): double; begin BelongsToRendering('CalculateAvgSprayThickness'); end;
function CalculateSDSprayThickness(i: integer): double; begin BelongsToRendering('CalculateSDSprayThickness'); end;
function CalculatePosAvgSprayThickness(i: integer): double; begin BelongsToRendering('CalculatePosAvgSprayThickness'); end;
function CalculatePosSDSprayThickness(i: integer): double; begin BelongsToRendering('CalculatePosSDSprayThickness'); end;
function CalculatePosMinSprayThickness(i: integer): double; begin BelongsToRendering('CalculatePosMinSprayThickness'); end;
function CalculateMinSprayThickness(i: integer): double; begin BelongsToRendering('CalculateMinSprayThickness'); end;
function CalculateMaxSprayThickness(i: integer): double; begin BelongsToRendering('CalculateMaxSprayThickness'); end;
function CalculateSprayCoverage(i: integer): double; begin BelongsToRendering('CalculateSprayCoverage'); end;
function GetPaintTargetTriangles(i: integer): TTriangles; begin BelongsToRendering('GetPaintTargetTriangles'); end;
procedure SetResultTrianglesColor(i: integer; colors: array of TPoint3D); begin BelongsToRendering('SetResultTrianglesColor'); end;
function GetCameraPixel(X, Y: integer): TRGBAColor; begin BelongsToRendering('GetCameraPixel'); end;

procedure SetFireScale(x, y, z: double); begin NotYetAvailable('SetFireScale'); end;
procedure SetFirePosition(x, y, z: double); begin NotYetAvailable('SetFirePosition'); end;
procedure StartFire; begin NotYetAvailable('StartFire'); end;
procedure StopFire; begin NotYetAvailable('StopFire'); end;
procedure StopSolidFire(R, I: integer); begin NotYetAvailable('StopSolidFire'); end;
procedure StartSolidFire(R, I: integer); begin NotYetAvailable('StartSolidFire'); end;

procedure SetGlobalSensorVin(i: integer; Vin: byte); begin HostCall(hSetGlobalSensorVin, [i, Vin]); end;
procedure SetSensorColor(R, i: integer; Red, Green, Blue: byte); begin NotYetAvailable('SetSensorColor'); end;

procedure SetThingColor(T, c: integer; Red, Green, Blue: byte); begin HostCall(hSetThingColor, [T, c, Red, Green, Blue]); end;
function GetThingRotMat(T: integer): Matrix; begin result := HostMatrix(hGetThingRotMat, [T]); end;
procedure SetThingRotationMat(T: integer; Rot: Matrix); begin CallMatrix(hSetThingRotationMat, [T], Rot); end;
function GetThingAgularVelMat(T: integer): Matrix; begin result := PointColumn(GetThingAngularVel(T)); end;
function GetThingSize(T: integer): TPoint3D; begin result := HostPoint(hGetThingSize, [T]); end;
procedure SetThingSize(T: integer; x, y, z: double); begin NotYetAvailable('SetThingSize'); end;
function AddThingBox(ID: string; mass, posx, posY, posZ, sizeX, sizeY, sizeZ: double; rgb24: integer): integer;
begin NotYetAvailable('AddThingBox'); result := -1; end;
function AddThingSphere(ID: string; mass, posX, posY, posZ, radius: double; rgb24: integer): integer;
begin NotYetAvailable('AddThingSphere'); result := -1; end;
function AddThingCylinder(ID: string; mass, posx, posY, posZ, radius, len: double; rgb24: integer): integer;
begin NotYetAvailable('AddThingCylinder'); result := -1; end;
function DeleteThing(ID: string): integer; begin NotYetAvailable('DeleteThing'); result := -1; end;
procedure MeshThing(ID, MeshFile, MeshShadowFile: string; MeshScale: double; MeshCastsShadows: boolean);
begin NotYetAvailable('MeshThing'); end;
procedure ClearThings; begin NotYetAvailable('ClearThings'); end;
procedure SetThingForce(T: integer; Fx, Fy, Fz: double); begin HostCall(hSetThingForce, [T, Fx, Fy, Fz]); end;
procedure SetThingForceAtRelPos(T: integer; Fx, Fy, Fz, Px, Py, Pz: double);
begin HostCall(hSetThingForceAtRelPos, [T, Fx, Fy, Fz, Px, Py, Pz]); end;
procedure SetThingRelForce(T: integer; Fx, Fy, Fz: double); begin HostCall(hSetThingRelForce, [T, Fx, Fy, Fz]); end;
procedure SetThingRelForceAtRelPos(T: integer; Fx, Fy, Fz, Px, Py, Pz: double);
begin HostCall(hSetThingRelForceAtRelPos, [T, Fx, Fy, Fz, Px, Py, Pz]); end;
procedure SetThingSurfaceMu(T: integer; mu, mu2: double); begin NotYetAvailable('SetThingSurfaceMu'); end;
function GetThingSpeed(T: integer): TPoint3D; begin result := HostPoint(hGetThingSpeed, [T]); end;
procedure SetThingSpeed(T: integer; vx, vy, vz: double); begin HostCall(hSetThingSpeed, [T, vx, vy, vz]); end;
procedure SetThingLinearVel(T: integer; x, y, z: double); begin HostCall(hSetThingLinearVel, [T, x, y, z]); end;
procedure SetThingAngularVel(T: integer; x, y, z: double); begin HostCall(hSetThingAngularVel, [T, x, y, z]); end;
function GetThingAngularVel(T: integer): TPoint3D; begin result := HostPoint(hGetThingAngularVel, [T]); end;

function GetShellPos(R, i: integer): TPoint3D; begin NotYetAvailable('GetShellPos'); end;
procedure SetShellColor(R, i: integer; Red, Green, Blue: byte); begin NotYetAvailable('SetShellColor'); end;
function GetShellColor(R, i: integer): TRGBAColor; begin NotYetAvailable('GetShellColor'); end;

function GetObstacleIndex(ID: string): integer; begin result := Round(HostCallS(hGetObstacleIndex, [], ID)); end;
procedure SetObstacleColor(I: integer; Red, Green, Blue: byte); begin NotYetAvailable('SetObstacleColor'); end;
function GetObstacleColor(I: integer): TRGBAColor;
var M: Matrix;
begin
  HostCall(hGetObstacleColor, [I]);
  M := HostValues;
  result.Red := Round(M.data[0]); result.Green := Round(M.data[1]);
  result.Blue := Round(M.data[2]); result.alpha := Round(M.data[3]);
end;
procedure SetObstaclePos(T: integer; x, y, z: double); begin NotYetAvailable('SetObstaclePos'); end;
function GetObstacleRotMat(T: integer): Matrix; begin result := HostMatrix(hGetObstacleRotMat, [T]); end;
procedure SetObstacleRotationMat(T: integer; Rot: Matrix); begin NotYetAvailable('SetObstacleRotationMat'); end;
function DeleteObstacle(ID: string): integer; begin NotYetAvailable('DeleteObstacle'); result := -1; end;

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
function GetAxisMotorSpeed(R, i: integer): double; begin NotYetAvailable('GetAxisMotorSpeed'); end;
function GetAxisMotorPos(R, i: integer): double; begin NotYetAvailable('GetAxisMotorPos'); end;
function GetAxisMotorPosDeg(R, i: integer): double; begin NotYetAvailable('GetAxisMotorPosDeg'); end;
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
procedure SetBeltSpeed(R, i: integer; nSpeed: double); begin NotYetAvailable('SetBeltSpeed'); end;
function GetBeltSpeed(R, i: integer): double; begin NotYetAvailable('GetBeltSpeed'); end;
procedure SetAxisSpring(R, i: integer; k, ZeroPos: double); begin HostCall(hSetAxisSpring, [R, i, k, ZeroPos]); end;


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

procedure S2SimPublishHUD;
begin
  HostCallS(hHUDText, [], HUDStrings.Text);
end;

initialization
  DefaultFormatSettings.DecimalSeparator := '.';
  HUDStrings := TStringList.Create;
  UDPDataRead := TMemoryStream.Create;
  CamBitmap := TBitmap.Create;
finalization
  CamBitmap.Free;
  UDPDataRead.Free;
  HUDStrings.Free;
end.
