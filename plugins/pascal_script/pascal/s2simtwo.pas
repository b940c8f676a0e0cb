{ S2Sim's SimTwo script support unit (written for S2Sim; no SimTwo source). It gives a SimTwo
  `control.pas`, compiled unchanged with Free Pascal -Mdelphi, what SimTwo's Pascal Script
  engine gives it: SimTwo's types and constants, its pure helpers with SimTwo's definitions,
  the Matrix API, and the host functions, each forwarding to the C++ host through one table
  filled at load (plugins/pascal_script/host_api.cpp). It comes last in the wrapper's `uses`,
  so its WriteLn, Sqr, Sign, Format, TStringList... shadow the RTL's (docs/scripting.md). }
unit s2simtwo;

{$mode delphi}{$H+}

interface

uses SysUtils, Classes, Math;

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

  Matrix = record
    data: array of double;
    rows, cols: Longword;
  end;

  TUDPBuffer = record
    data: array[0..1499] of byte;
    MessSize, ReadDisp: integer;
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
  Host: THostTable;

{ --- pure helpers, SimTwo's definitions --- }
function Format(const sFormat: string; const Args: array of const): string;
function Rad(angle: double): double;
function Deg(angle: double): double;
function Sqr(X: double): double;
function Sign(a: double): double;
function Sat(a, limit: double): double;
function ATan2(y, x: double): double;
function DiffAngle(a1, a2: double): double;
function NormalizeAngle(ang: double): double;
function Dist(x, y: double): double;
function ACos2(y, x: double): double;
function ASin2(y, x: double): double;
function random01: double;
function Pi: double;

{ --- Matrix (SimTwo's dynmatrix API) --- }
function Mzeros(r, c: Longword): Matrix;
function Meye(n: Longword): Matrix;
function Minc(r, c: Longword): Matrix;
procedure MSetSize(var M: Matrix; r, c: Longword);
procedure Msetv(var M: Matrix; r, c: Longword; v: double);
function Mgetv(const M: Matrix; r, c: Longword): double;
procedure MUsetv(var M: Matrix; r, c: Longword; v: double);
function MUgetv(const M: Matrix; r, c: Longword): double;
function MNumRows(const M: Matrix): Longword;
function MNumCols(const M: Matrix): Longword;
function Madd(const A, B: Matrix): Matrix;
function Msub(const A, B: Matrix): Matrix;
function Mmult(const A, B: Matrix): Matrix;
function MmultReal(const A: Matrix; k: double): Matrix;
function MaddReal(const A: Matrix; k: double): Matrix;
function MsubReal(const A: Matrix; k: double): Matrix;
function Mneg(const A: Matrix): Matrix;
function Mtran(const A: Matrix): Matrix;
function Minv(const A: Matrix): Matrix;
function MOneCol(const A: Matrix; c: Longword): Matrix;
function MOneRow(const A: Matrix; r: Longword): Matrix;
function Mmin(const A: Matrix): double;
function Mmax(const A: Matrix): double;
function MmaxAbs(const A: Matrix): double;

{ --- net buffer (SimTwo's rlan helpers) --- }
procedure ClearUDPBuffer(var Buf: TUDPBuffer);
procedure NetPutByte(var Buf: TUDPBuffer; value: byte);
procedure NetPutWord(var Buf: TUDPBuffer; value: word);
procedure NetPutShort(var Buf: TUDPBuffer; value: smallint);
procedure NetPutInt(var Buf: TUDPBuffer; value: integer);
procedure NetPutFloat(var Buf: TUDPBuffer; value: single);
function NetGetByte(var Buf: TUDPBuffer): byte;
function NetGetWord(var Buf: TUDPBuffer): word;
function NetGetInt(var Buf: TUDPBuffer): integer;
function NetGetFloat(var Buf: TUDPBuffer): single;
function NetStringBuffer(const Buf: TUDPBuffer): string;

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

{ --- Format: SimTwo's Win64 Format prints a bare %g / %e with 15 digits, FPC's with 17 --- }

function Format(const sFormat: string; const Args: array of const): string;
var s: string; i, j: integer; hasPrec: boolean;
begin
  s := '';
  i := 1;
  while i <= Length(sFormat) do begin
    if sFormat[i] <> '%' then begin s := s + sFormat[i]; Inc(i); continue; end;
    if (i < Length(sFormat)) and (sFormat[i + 1] = '%') then begin s := s + '%%'; Inc(i, 2); continue; end;
    j := i + 1;
    hasPrec := false;
    while (j <= Length(sFormat)) and (sFormat[j] in ['0'..'9', '-', ':', '.', '*']) do begin
      if sFormat[j] = '.' then hasPrec := true;
      Inc(j);
    end;
    if (j <= Length(sFormat)) and (UpCase(sFormat[j]) in ['G', 'E']) and not hasPrec then
      s := s + Copy(sFormat, i, j - i) + '.15' + sFormat[j]
    else
      s := s + Copy(sFormat, i, j - i + 1);
    i := j + 1;
  end;
  result := SysUtils.Format(s, Args);
end;

function Rad(angle: double): double; begin result := angle * System.Pi / 180; end;
function Deg(angle: double): double; begin result := angle * 180 / System.Pi; end;
function Sqr(X: double): double; begin result := X * X; end;
function Sign(a: double): double; begin if a < 0 then result := -1 else result := 1; end;
function Pi: double; begin result := System.Pi; end;

function Sat(a, limit: double): double;
begin
  if a > limit then result := limit
  else if a < -limit then result := -limit
  else result := a;
end;

function ATan2(y, x: double): double;
begin
  if (abs(x) < 1e-10) and (abs(y) < 1e-10) then result := 0
  else result := Math.ArcTan2(y, x);
end;

function DiffAngle(a1, a2: double): double;
begin
  result := a1 - a2;
  result := result - 2 * System.Pi * Int(result / (2 * System.Pi));
  if result > System.Pi then result := result - 2 * System.Pi
  else if result < -System.Pi then result := result + 2 * System.Pi;
end;

function NormalizeAngle(ang: double): double;
begin
  result := ang - 2 * System.Pi * Floor((ang + System.Pi) / (2 * System.Pi));
end;

function Dist(x, y: double): double; begin result := sqrt(x * x + y * y); end;

function ACos2(y, x: double): double;
begin
  result := Math.ArcCos(Math.EnsureRange(x, -1, 1));
  if y < 0 then result := -result;
end;

function ASin2(y, x: double): double;
var s: double;
begin
  s := Math.ArcSin(Math.EnsureRange(y, -1, 1));
  if x >= 0 then result := s
  else if y > 0 then result := System.Pi + s
  else result := -System.Pi + s;
end;

function random01: double; begin result := System.Random; end;

{ --- Matrix: row-major, element (r, c) at data[c + r * cols] --- }

procedure MatrixError(const msg: string);
begin
  raise Exception.Create(msg);
end;

procedure MSetSize(var M: Matrix; r, c: Longword);
begin
  M.rows := r; M.cols := c;
  SetLength(M.data, r * c);
end;

function Mzeros(r, c: Longword): Matrix;
var i: integer;
begin
  MSetSize(result, r, c);
  for i := 0 to High(result.data) do result.data[i] := 0;
end;

function Meye(n: Longword): Matrix;
var i: Longword;
begin
  result := Mzeros(n, n);
  if n > 0 then for i := 0 to n - 1 do result.data[i + i * n] := 1;
end;

function Minc(r, c: Longword): Matrix;
var i: integer;
begin
  MSetSize(result, r, c);
  for i := 0 to High(result.data) do result.data[i] := i;
end;

function BadElement(const M: Matrix; r, c: Longword): string;
begin
  result := SysUtils.Format('Invalid (row,col) value. Matrix is (%d,%d), element required is (%d,%d)',
    [M.rows, M.cols, r, c]);
end;

procedure Msetv(var M: Matrix; r, c: Longword; v: double);
begin
  if (r >= M.rows) or (c >= M.cols) then MatrixError(BadElement(M, r, c));
  SetLength(M.data, Length(M.data));  { unshare before writing: value semantics }
  M.data[c + r * M.cols] := v;
end;

function Mgetv(const M: Matrix; r, c: Longword): double;
begin
  if (r >= M.rows) or (c >= M.cols) then MatrixError(BadElement(M, r, c));
  result := M.data[c + r * M.cols];
end;

procedure MUsetv(var M: Matrix; r, c: Longword; v: double);
begin
  if (r >= M.rows) or (c >= M.cols) then exit;
  SetLength(M.data, Length(M.data));
  M.data[c + r * M.cols] := v;
end;

function MUgetv(const M: Matrix; r, c: Longword): double;
begin
  if (r >= M.rows) or (c >= M.cols) then result := 0
  else result := M.data[c + r * M.cols];
end;

function MNumRows(const M: Matrix): Longword; begin result := M.rows; end;
function MNumCols(const M: Matrix): Longword; begin result := M.cols; end;

function Madd(const A, B: Matrix): Matrix;
var i: integer;
begin
  if (A.rows <> B.rows) or (A.cols <> B.cols) then
    MatrixError(SysUtils.Format('Cannot add matrix (%d,%d) with matrix (%d,%d)', [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] + B.data[i];
end;

function Msub(const A, B: Matrix): Matrix;
var i: integer;
begin
  if (A.rows <> B.rows) or (A.cols <> B.cols) then
    MatrixError(SysUtils.Format('Cannot subtract matrix (%d,%d) with matrix (%d,%d)', [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] - B.data[i];
end;

function Mmult(const A, B: Matrix): Matrix;
var r, c, k: Longword; s: double;
begin
  if A.cols <> B.rows then
    MatrixError(SysUtils.Format('Cannot multiply matrix (%d,%d) with matrix (%d,%d)', [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, B.cols);
  if (A.rows = 0) or (B.cols = 0) then exit;
  for r := 0 to A.rows - 1 do
    for c := 0 to B.cols - 1 do begin
      s := 0;
      if A.cols > 0 then
        for k := 0 to A.cols - 1 do s := s + A.data[k + r * A.cols] * B.data[c + k * B.cols];
      result.data[c + r * B.cols] := s;
    end;
end;

function MmultReal(const A: Matrix; k: double): Matrix;
var i: integer;
begin
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] * k;
end;

function MaddReal(const A: Matrix; k: double): Matrix;
var i: integer;
begin
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] + k;
end;

function MsubReal(const A: Matrix; k: double): Matrix;
var i: integer;
begin
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] - k;
end;

function Mneg(const A: Matrix): Matrix; begin result := MmultReal(A, -1); end;

function Mtran(const A: Matrix): Matrix;
var r, c: Longword;
begin
  MSetSize(result, A.cols, A.rows);
  if (A.rows = 0) or (A.cols = 0) then exit;
  for r := 0 to A.rows - 1 do
    for c := 0 to A.cols - 1 do result.data[r + c * A.rows] := A.data[c + r * A.cols];
end;

{ Gauss-Jordan with full pivoting. }
function Minv(const A: Matrix): Matrix;
var n, i, j, k, pr, pc: integer; big, t: double;
    a2: array of double; rowp, colp: array of integer; piv: array of boolean;
begin
  if A.rows <> A.cols then MatrixError('Cannot invert non-square matrix');
  n := A.rows;
  SetLength(a2, n * n);
  for i := 0 to n * n - 1 do a2[i] := A.data[i];
  SetLength(rowp, n); SetLength(colp, n); SetLength(piv, n);
  for i := 0 to n - 1 do piv[i] := false;
  for i := 0 to n - 1 do begin
    big := 0; pr := 0; pc := 0;
    for j := 0 to n - 1 do
      if not piv[j] then
        for k := 0 to n - 1 do
          if (not piv[k]) and (abs(a2[k + j * n]) >= big) then begin
            big := abs(a2[k + j * n]); pr := j; pc := k;
          end;
    piv[pc] := true;
    if pr <> pc then
      for k := 0 to n - 1 do begin
        t := a2[k + pr * n]; a2[k + pr * n] := a2[k + pc * n]; a2[k + pc * n] := t;
      end;
    rowp[i] := pr; colp[i] := pc;
    if a2[pc + pc * n] = 0 then MatrixError('Singular matrix: Pivot is 0');
    t := 1 / a2[pc + pc * n];
    a2[pc + pc * n] := 1;
    for k := 0 to n - 1 do a2[k + pc * n] := a2[k + pc * n] * t;
    for j := 0 to n - 1 do
      if j <> pc then begin
        t := a2[pc + j * n];
        a2[pc + j * n] := 0;
        for k := 0 to n - 1 do a2[k + j * n] := a2[k + j * n] - a2[k + pc * n] * t;
      end;
  end;
  for i := n - 1 downto 0 do
    if rowp[i] <> colp[i] then
      for j := 0 to n - 1 do begin
        t := a2[rowp[i] + j * n]; a2[rowp[i] + j * n] := a2[colp[i] + j * n]; a2[colp[i] + j * n] := t;
      end;
  MSetSize(result, n, n);
  for i := 0 to n * n - 1 do result.data[i] := a2[i];
end;

function MOneCol(const A: Matrix; c: Longword): Matrix;
var r: Longword;
begin
  if c >= A.cols then MatrixError(BadElement(A, 0, c));
  MSetSize(result, A.rows, 1);
  if A.rows > 0 then for r := 0 to A.rows - 1 do result.data[r] := A.data[c + r * A.cols];
end;

function MOneRow(const A: Matrix; r: Longword): Matrix;
var c: Longword;
begin
  if r >= A.rows then MatrixError(BadElement(A, r, 0));
  MSetSize(result, 1, A.cols);
  if A.cols > 0 then for c := 0 to A.cols - 1 do result.data[c] := A.data[c + r * A.cols];
end;

function Mmin(const A: Matrix): double;
var i: integer;
begin
  result := A.data[0];
  for i := 1 to High(A.data) do if A.data[i] < result then result := A.data[i];
end;

function Mmax(const A: Matrix): double;
var i: integer;
begin
  result := A.data[0];
  for i := 1 to High(A.data) do if A.data[i] > result then result := A.data[i];
end;

function MmaxAbs(const A: Matrix): double;
var i: integer;
begin
  result := abs(A.data[0]);
  for i := 1 to High(A.data) do if abs(A.data[i]) > result then result := abs(A.data[i]);
end;

{ --- net buffer: little-endian, at most 1499 bytes (SimTwo's limit) --- }

procedure ClearUDPBuffer(var Buf: TUDPBuffer);
begin
  FillChar(Buf.data, SizeOf(Buf.data), 0);
  Buf.MessSize := 0;  { ReadDisp is kept, as SimTwo does }
end;

procedure NetPut(var Buf: TUDPBuffer; const src; size: integer);
begin
  if Buf.MessSize + size >= 1500 then raise Exception.Create('Write: UDP Message size too big');
  Move(src, Buf.data[Buf.MessSize], size);
  Inc(Buf.MessSize, size);
end;

procedure NetGet(var Buf: TUDPBuffer; var dst; size: integer);
begin
  if Buf.ReadDisp + size > Buf.MessSize then raise Exception.Create('Read: UDP Message size too big');
  Move(Buf.data[Buf.ReadDisp], dst, size);
  Inc(Buf.ReadDisp, size);
end;

procedure NetPutByte(var Buf: TUDPBuffer; value: byte); begin NetPut(Buf, value, 1); end;
procedure NetPutWord(var Buf: TUDPBuffer; value: word); begin NetPut(Buf, value, 2); end;
procedure NetPutShort(var Buf: TUDPBuffer; value: smallint); begin NetPut(Buf, value, 2); end;
procedure NetPutInt(var Buf: TUDPBuffer; value: integer); begin NetPut(Buf, value, 4); end;
procedure NetPutFloat(var Buf: TUDPBuffer; value: single); begin NetPut(Buf, value, 4); end;
function NetGetByte(var Buf: TUDPBuffer): byte; begin NetGet(Buf, result, 1); end;
function NetGetWord(var Buf: TUDPBuffer): word; begin NetGet(Buf, result, 2); end;
function NetGetInt(var Buf: TUDPBuffer): integer; begin NetGet(Buf, result, 4); end;
function NetGetFloat(var Buf: TUDPBuffer): single; begin NetGet(Buf, result, 4); end;

function NetStringBuffer(const Buf: TUDPBuffer): string;
begin
  SetString(result, PChar(@Buf.data[0]), Buf.MessSize);
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

procedure S2SimPublishHUD;
begin
  HostCallS(hHUDText, [], HUDStrings.Text);
end;

initialization
  DefaultFormatSettings.DecimalSeparator := '.';
  HUDStrings := TStringList.Create;
finalization
  HUDStrings.Free;
end.
