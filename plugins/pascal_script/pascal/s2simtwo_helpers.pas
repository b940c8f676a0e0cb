{ SimTwo's pure helpers for scripts (written for S2Sim after SimTwo's definitions; no SimTwo
  source): Utils' angles and frames, Editor's number helpers, rlan's net buffer, and Format
  with SimTwo's 15-digit bare %g. }
unit s2simtwo_helpers;

{$mode delphi}{$H+}

interface

uses SysUtils, Math, s2simtwo_matrix;

type
  TUDPBuffer = record
    data: array[0..1499] of byte;
    MessSize, ReadDisp: integer;
  end;


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
function NetStringBuffer(var Buf: TUDPBuffer): string;

function FloatAsInteger(X: single): integer;
function IntegerAsFloat(X: integer): single;
function TranslateAndRotate(var rx, ry: double; px, py, tx, ty, teta: double): double;
function RotateAndTranslate(var rx, ry: double; px, py, tx, ty, teta: double): double;
function RotateAroundPoint(var rx, ry: double; px, py, cx, cy, teta: double): double;
function BiLinInterp(Surf: Matrix; xmin, xmax, ymin, ymax, x, y: double): double;

procedure NetBufferSeek(var Buf: TUDPBuffer; disp: integer);
procedure NetPutString(var Buf: TUDPBuffer; str: string);
procedure NetPutAngle(var Buf: TUDPBuffer; value: double);
function NetPeekByte(var Buf: TUDPBuffer): byte;
function NetGetShort(var Buf: TUDPBuffer): SmallInt;
function NetGetString(var Buf: TUDPBuffer): string;
function NetGetAngle(var Buf: TUDPBuffer): double;
procedure Test(var B: double);

implementation

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

function NetStringBuffer(var Buf: TUDPBuffer): string;
begin
  SetString(result, PChar(@Buf.data[0]), Buf.MessSize);
end;

{ The bits of a single as an integer and back (Editor's FloatAsInteger, IntegerAsFloat). }
function FloatAsInteger(X: single): integer;
begin
  Move(X, result, SizeOf(result));
end;

function IntegerAsFloat(X: integer): single;
begin
  Move(X, result, SizeOf(result));
end;

{ Utils' frame changes write (rx, ry); SimTwo registers them as functions of procedures, so
  their value is whatever a register held: here 0. }
function TranslateAndRotate(var rx, ry: double; px, py, tx, ty, teta: double): double;
var vx, vy: double;
begin
  vx := px + tx;
  vy := py + ty;
  rx := vx * cos(teta) - vy * sin(teta);
  ry := vx * sin(teta) + vy * cos(teta);
  result := 0;
end;

function RotateAndTranslate(var rx, ry: double; px, py, tx, ty, teta: double): double;
begin
  rx := px * cos(teta) - py * sin(teta) + tx;
  ry := px * sin(teta) + py * cos(teta) + ty;
  result := 0;
end;

function RotateAroundPoint(var rx, ry: double; px, py, cx, cy, teta: double): double;
begin
  rx := (px - cx) * cos(teta) - (py - cy) * sin(teta) + cx;
  ry := (px - cx) * sin(teta) + (py - cy) * cos(teta) + cy;
  result := 0;
end;

{ Surf samples a surface on a regular grid: columns from xmin to xmax, rows from ymin to ymax;
  (x, y) outside is taken at the nearest edge. }
function BiLinInterp(Surf: Matrix; xmin, xmax, ymin, ymax, x, y: double): double;
var fx, fy, tx, ty: double; c0, r0, c1, r1: integer;
begin
  if (Surf.rows = 0) or (Surf.cols = 0) then raise Exception.Create('BiLinInterp: empty matrix');
  if Surf.cols = 1 then fx := 0
  else fx := EnsureRange((x - xmin) / (xmax - xmin), 0, 1) * (Surf.cols - 1);
  if Surf.rows = 1 then fy := 0
  else fy := EnsureRange((y - ymin) / (ymax - ymin), 0, 1) * (Surf.rows - 1);
  c0 := Floor(fx); r0 := Floor(fy);
  c1 := Min(c0 + 1, integer(Surf.cols) - 1); r1 := Min(r0 + 1, integer(Surf.rows) - 1);
  tx := fx - c0; ty := fy - r0;
  result := (1 - ty) * ((1 - tx) * Surf.data[c0 + r0 * integer(Surf.cols)] + tx * Surf.data[c1 + r0 * integer(Surf.cols)]) +
            ty * ((1 - tx) * Surf.data[c0 + r1 * integer(Surf.cols)] + tx * Surf.data[c1 + r1 * integer(Surf.cols)]);
end;

procedure NetBufferSeek(var Buf: TUDPBuffer; disp: integer);
begin
  if (disp > Buf.MessSize) or (disp = -1) then disp := Buf.MessSize;
  Buf.ReadDisp := disp;
end;

{ A word with the length, then the characters. }
procedure NetPutString(var Buf: TUDPBuffer; str: string);
begin
  if Length(str) > 65535 then raise Exception.Create('Write: UDP Message size too big');
  NetPutWord(Buf, Length(str));
  if Length(str) > 0 then NetPut(Buf, str[1], Length(str));
end;

{ An angle as a word: (NormalizeAngle(a) + pi) * 10000, rounded. }
procedure NetPutAngle(var Buf: TUDPBuffer; value: double);
begin
  NetPutWord(Buf, Round((NormalizeAngle(value) + System.Pi) * 10000));
end;

function NetPeekByte(var Buf: TUDPBuffer): byte;
begin
  result := 0;
  if (Buf.ReadDisp < 0) or (Buf.ReadDisp > Buf.MessSize) or (Buf.ReadDisp > High(Buf.data)) then exit;
  result := Buf.data[Buf.ReadDisp];
end;

function NetGetShort(var Buf: TUDPBuffer): SmallInt; begin NetGet(Buf, result, 2); end;

function NetGetString(var Buf: TUDPBuffer): string;
var size: word;
begin
  result := '';
  size := NetGetWord(Buf);
  if size = 0 then exit;
  SetLength(result, size);
  NetGet(Buf, result[1], size);
end;

function NetGetAngle(var Buf: TUDPBuffer): double;
begin
  result := NormalizeAngle(NetGetWord(Buf) / 10000 - System.Pi);
end;

{ rlan's Test leaves B as it is. }
procedure Test(var B: double);
begin
end;

end.
