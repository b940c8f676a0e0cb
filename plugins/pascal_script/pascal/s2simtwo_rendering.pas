{ SimTwo's canvas, camera and spray-paint routines (written for S2Sim; no SimTwo source):
  declared with their types so that scripts compile; each raises "... belongs to rendering"
  until S2Sim renders them. }
unit s2simtwo_rendering;

{$mode delphi}{$H+}

interface

uses SysUtils, Types, s2simtwo_types;

type
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


var
  CamBitmap: TBitmap;  { its canvas raises }

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

implementation

procedure TCanvas.TextOut(X, Y: integer; const Text: string); begin BelongsToRendering('TCanvas.TextOut'); end;
procedure TCanvas.FillRect(const R: TRect); begin BelongsToRendering('TCanvas.FillRect'); end;
procedure TCanvas.Rectangle(X1, Y1, X2, Y2: integer); begin BelongsToRendering('TCanvas.Rectangle'); end;
procedure TCanvas.Ellipse(X1, Y1, X2, Y2: integer); begin BelongsToRendering('TCanvas.Ellipse'); end;
procedure TCanvas.MoveTo(X, Y: integer); begin BelongsToRendering('TCanvas.MoveTo'); end;
procedure TCanvas.LineTo(X, Y: integer); begin BelongsToRendering('TCanvas.LineTo'); end;

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

initialization
  CamBitmap := TBitmap.Create;
  CamBitmap.Canvas := TCanvas.Create;
  CamBitmap.Canvas.Brush := TCanvasTool.Create;
  CamBitmap.Canvas.Pen := TCanvasTool.Create;
  CamBitmap.Canvas.Font := TCanvasTool.Create;
finalization
  CamBitmap.Canvas.Font.Free;
  CamBitmap.Canvas.Pen.Free;
  CamBitmap.Canvas.Brush.Free;
  CamBitmap.Canvas.Free;
  CamBitmap.Free;
end.
