{ SimTwo's A* path planner for scripts (PathFinder's routines; written for S2Sim, no SimTwo
  source): a 128 x 128 grid whose border is an obstacle, eight neighbours (a diagonal step
  costs sqrt 2), the heuristic EucliDistK times the straight distance to the target. A start
  or target inside an obstacle moves to the nearest free cell along the eight directions.
  The path runs from the start to the target, both included; no path leaves it empty. }
unit s2simtwo_astar;

{$mode delphi}{$H+}

interface

uses SysUtils, Math, Types;

procedure ClearAStarMap;
procedure SetupAStarMap(xi, yi, xt, yt: integer; nEucliDistK: double);
procedure AddAStarObstacleCircle(xc, yc, r: double);
procedure AddAStarObstacleRect(xi, yi, xf, yf: double);
procedure CalcAStarPath;
function GetAStarPathPoint(i: integer): TPoint;
function GetAStarPathCount: integer;

implementation

const
  GridSize = 128;
  DX: array[0..7] of integer = (1, 1, 0, -1, -1, -1, 0, 1);
  DY: array[0..7] of integer = (0, -1, -1, -1, 0, 1, 1, 1);

var
  Blocked: array[0..GridSize - 1, 0..GridSize - 1] of boolean;
  StartX, StartY, TargetX, TargetY: integer;
  EucliDistK: double;
  Path: array of TPoint;

function Inside(x, y: integer): boolean;
begin
  result := (x >= 0) and (y >= 0) and (x < GridSize) and (y < GridSize);
end;

procedure Block(x, y: integer);
begin
  if Inside(x, y) then Blocked[x, y] := true;
end;

procedure ClearAStarMap;
var x, y: integer;
begin
  for x := 0 to GridSize - 1 do
    for y := 0 to GridSize - 1 do
      Blocked[x, y] := (x = 0) or (y = 0) or (x = GridSize - 1) or (y = GridSize - 1);
end;

procedure SetupAStarMap(xi, yi, xt, yt: integer; nEucliDistK: double);
begin
  StartX := xi; StartY := yi; TargetX := xt; TargetY := yt;
  EucliDistK := nEucliDistK;
end;

{ The cells of rows yc - i and yc + i within the circle, as SimTwo fills them. }
procedure AddAStarObstacleCircle(xc, yc, r: double);
var i, j: integer; half: double;
begin
  for i := 0 to Round(r) do begin
    half := sqrt(Max(0, r * r - i * i));
    for j := -Round(half) + 1 to Round(half) - 1 do begin
      Block(Round(xc + j), Round(yc + i));
      Block(Round(xc + j), Round(yc - i));
    end;
  end;
end;

procedure AddAStarObstacleRect(xi, yi, xf, yf: double);
var x, y: integer;
begin
  for y := Round(yi) to Round(yf) do
    for x := Round(xi) to Round(xf) do Block(x, y);
end;

procedure MoveOutOfObstacle(var px, py: integer);
var step, d, x, y: integer;
begin
  if not Inside(px, py) then raise Exception.Create(
    SysUtils.Format('CalcAStarPath: point (%d,%d) outside the %dx%d map', [px, py, GridSize, GridSize]));
  if not Blocked[px, py] then exit;
  for step := 1 to GridSize - 1 do
    for d := 0 to 7 do begin
      x := px + DX[d] * step;
      y := py + DY[d] * step;
      if Inside(x, y) and not Blocked[x, y] then begin px := x; py := y; exit; end;
    end;
end;

procedure CalcAStarPath;
var g: array[0..GridSize - 1, 0..GridSize - 1] of double;
    parent: array[0..GridSize - 1, 0..GridSize - 1] of integer;
    closed: array[0..GridSize - 1, 0..GridSize - 1] of boolean;
    heap: array of integer;  { cells x * GridSize + y, by f = g + h }
    count, x, y, d, nx, ny, cell, n, i, c: integer; ng, step: double;

  function F(cell: integer): double;
  var cx, cy: integer;
  begin
    cx := cell div GridSize; cy := cell mod GridSize;
    result := g[cx, cy] + EucliDistK * sqrt(Sqr(cx - TargetX) + Sqr(cy - TargetY));
  end;

  procedure Push(cell: integer);
  var i, p, t: integer;
  begin
    if count = Length(heap) then SetLength(heap, 2 * count + 16);
    heap[count] := cell;
    i := count;
    Inc(count);
    while i > 0 do begin
      p := (i - 1) div 2;
      if F(heap[p]) <= F(heap[i]) then break;
      t := heap[p]; heap[p] := heap[i]; heap[i] := t;
      i := p;
    end;
  end;

  function Pop: integer;
  var i, l, m, t: integer;
  begin
    result := heap[0];
    Dec(count);
    heap[0] := heap[count];
    i := 0;
    while true do begin
      l := 2 * i + 1;
      if l >= count then break;
      m := l;
      if (l + 1 < count) and (F(heap[l + 1]) < F(heap[l])) then m := l + 1;
      if F(heap[i]) <= F(heap[m]) then break;
      t := heap[m]; heap[m] := heap[i]; heap[i] := t;
      i := m;
    end;
  end;

begin
  MoveOutOfObstacle(StartX, StartY);
  MoveOutOfObstacle(TargetX, TargetY);
  for x := 0 to GridSize - 1 do
    for y := 0 to GridSize - 1 do begin
      g[x, y] := Infinity; parent[x, y] := -1; closed[x, y] := false;
    end;
  count := 0;
  SetLength(heap, 0);
  g[StartX, StartY] := 0;
  Push(StartX * GridSize + StartY);
  while count > 0 do begin
    cell := Pop;
    x := cell div GridSize; y := cell mod GridSize;
    if closed[x, y] then continue;
    closed[x, y] := true;
    if (x = TargetX) and (y = TargetY) then break;
    for d := 0 to 7 do begin
      nx := x + DX[d]; ny := y + DY[d];
      if not Inside(nx, ny) or Blocked[nx, ny] or closed[nx, ny] then continue;
      if odd(d) then step := sqrt(2) else step := 1;
      ng := g[x, y] + step;
      if ng < g[nx, ny] then begin
        g[nx, ny] := ng;
        parent[nx, ny] := cell;
        Push(nx * GridSize + ny);
      end;
    end;
  end;
  SetLength(Path, 0);
  if not closed[TargetX, TargetY] then exit;
  n := 1;
  c := TargetX * GridSize + TargetY;
  while c <> StartX * GridSize + StartY do begin c := parent[c div GridSize, c mod GridSize]; Inc(n); end;
  SetLength(Path, n);
  c := TargetX * GridSize + TargetY;
  for i := n - 1 downto 0 do begin
    Path[i].x := c div GridSize; Path[i].y := c mod GridSize;
    if i > 0 then c := parent[c div GridSize, c mod GridSize];
  end;
end;

{ Past the end: the last point, as SimTwo; an empty path raises. }
function GetAStarPathPoint(i: integer): TPoint;
begin
  if Length(Path) = 0 then raise Exception.Create('GetAStarPathPoint: there is no path');
  if i >= Length(Path) then i := High(Path);
  if i < 0 then raise Exception.Create(SysUtils.Format('List index (%d) out of bounds', [i]));
  result := Path[i];
end;

function GetAStarPathCount: integer;
begin
  result := Length(Path);
end;

initialization
  ClearAStarMap;
end.
