{ SimTwo's spray-painting routines for scripts (written for S2Sim after SimTwo's behaviour; no
  SimTwo source): the guns' on/off inputs, the painting targets' geometry and the statistics of
  their paint, forwarded to the C++ host (plugins/pascal_script/host_paint.cpp). The types are
  SimTwo's (s2simtwo_types). }
unit s2simtwo_paint;

{$mode delphi}{$H+}

interface

uses SysUtils, s2simtwo_types, s2simtwo;

procedure SetSprayGunOn(i: integer);
procedure SetSprayGunOff(i: integer);
function GetPaintGunMinDist(i: integer): double;
function GetPaintTargetExtents(i: integer): TExtents;
procedure ResetPaintTargetPaint(i: integer);
procedure SetPaintTargetPaintMode(i: integer; paintMode: TPaintVisuals);
function GetPaintTargetTriangles(i: integer): TTriangles;
procedure SetResultTrianglesColor(i: integer; colors: array of TPoint3D);
function CalculateSprayThicknessHistogram(i: integer; numberOfBins: integer): THistogram;
function CalculateAvgSprayThickness(i: integer): double;
function CalculateSDSprayThickness(i: integer): double;
function CalculatePosAvgSprayThickness(i: integer): double;
function CalculatePosSDSprayThickness(i: integer): double;
function CalculatePosMinSprayThickness(i: integer): double;
function CalculateMinSprayThickness(i: integer): double;
function CalculateMaxSprayThickness(i: integer): double;
function CalculateSprayCoverage(i: integer): double;

implementation

type
  TDoubles = array[0..(MaxInt div SizeOf(double)) - 1] of double;
  PDoubles = ^TDoubles;

procedure SetSprayGunOn(i: integer); begin S2SimHostCall(hSetSprayGunOn, [i]); end;
procedure SetSprayGunOff(i: integer); begin S2SimHostCall(hSetSprayGunOff, [i]); end;
function GetPaintGunMinDist(i: integer): double; begin result := S2SimHostCall(hGetPaintGunMinDist, [i]); end;
procedure ResetPaintTargetPaint(i: integer); begin S2SimHostCall(hResetPaintTargetPaint, [i]); end;
procedure SetPaintTargetPaintMode(i: integer; paintMode: TPaintVisuals);
begin S2SimHostCall(hSetPaintTargetPaintMode, [i, Ord(paintMode)]); end;

function GetPaintTargetExtents(i: integer): TExtents;
var p: PDoubles;
begin
  S2SimHostCall(hGetPaintTargetExtents, [i]);
  S2SimHostNumbers(PDouble(p));
  result.Min.x := p^[0]; result.Min.y := p^[1]; result.Min.z := p^[2];
  result.Max.x := p^[3]; result.Max.y := p^[4]; result.Max.z := p^[5];
end;

function PointAt(p: PDoubles; k: integer): TPoint3D;
begin
  result.x := p^[k]; result.y := p^[k + 1]; result.z := p^[k + 2];
end;

{ The host's numbers: the triangle count, then per triangle its three vertices, centre and
  normal (x, y, z each), its area, its neighbour count and their indices. }
function GetPaintTargetTriangles(i: integer): TTriangles;
var p: PDoubles; n, t, k, m, j: integer;
begin
  S2SimHostCall(hGetPaintTargetTriangles, [i]);
  S2SimHostNumbers(PDouble(p));
  n := Round(p^[0]);
  SetLength(result, n);
  k := 1;
  for t := 0 to n - 1 do begin
    result[t].vertice0 := PointAt(p, k);
    result[t].vertice1 := PointAt(p, k + 3);
    result[t].vertice2 := PointAt(p, k + 6);
    result[t].center := PointAt(p, k + 9);
    result[t].normal := PointAt(p, k + 12);
    result[t].area := p^[k + 15];
    m := Round(p^[k + 16]);
    SetLength(result[t].neighbors, m);
    for j := 0 to m - 1 do result[t].neighbors[j] := Round(p^[k + 17 + j]);
    k := k + 17 + m;
  end;
end;

procedure SetResultTrianglesColor(i: integer; colors: array of TPoint3D);
var buf: array of double; c: integer;
begin
  SetLength(buf, 2 + 3 * Length(colors));
  buf[0] := i;
  buf[1] := Length(colors);
  for c := 0 to High(colors) do begin
    buf[2 + 3 * c] := colors[c].x;
    buf[3 + 3 * c] := colors[c].y;
    buf[4 + 3 * c] := colors[c].z;
  end;
  S2SimHostCall(hSetResultTrianglesColor, buf);
end;

{ The host's numbers: the bin count n, the n upper limits, the n heights. }
function CalculateSprayThicknessHistogram(i: integer; numberOfBins: integer): THistogram;
var p: PDoubles; n, b: integer;
begin
  S2SimHostCall(hCalculateSprayThicknessHistogram, [i, numberOfBins]);
  S2SimHostNumbers(PDouble(p));
  n := Round(p^[0]);
  SetLength(result.binUpperLimit, n);
  SetLength(result.binHeight, n);
  for b := 0 to n - 1 do begin
    result.binUpperLimit[b] := p^[1 + b];
    result.binHeight[b] := Round(p^[1 + n + b]);
  end;
end;

function CalculateAvgSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculateAvgSprayThickness, [i]); end;
function CalculateSDSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculateSDSprayThickness, [i]); end;
function CalculatePosAvgSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculatePosAvgSprayThickness, [i]); end;
function CalculatePosSDSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculatePosSDSprayThickness, [i]); end;
function CalculatePosMinSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculatePosMinSprayThickness, [i]); end;
function CalculateMinSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculateMinSprayThickness, [i]); end;
function CalculateMaxSprayThickness(i: integer): double;
begin result := S2SimHostCall(hCalculateMaxSprayThickness, [i]); end;
function CalculateSprayCoverage(i: integer): double;
begin result := S2SimHostCall(hCalculateSprayCoverage, [i]); end;

end.
