{ SimTwo's canvas and camera routines (written for S2Sim; no SimTwo source):
  declared with their types so that scripts compile; each raises "... belongs to rendering"
  until S2Sim renders them. }
unit s2simtwo_rendering;

{$mode delphi}{$H+}

interface

uses SysUtils, Types, s2simtwo_types;

type
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
