{ SimTwo's canvas and camera routines (written for S2Sim; no SimTwo source): declared with
  their types so that scripts compile. The canvas drawing raises "... belongs to rendering"
  until S2Sim renders it; the camera image reads (GetCameraPixel, CamBitmap's Width, Height
  and Canvas.Pixels[X, Y]) ask the C++ host (plugins/pascal_script/host_camera.cpp) for the
  last <camera> shell's image, in SimTwo's 640 x 480 coordinates. }
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
  private
    function GetPixel(X, Y: integer): TColor;
    procedure SetPixel(X, Y: integer; c: TColor);
  public
    Brush, Pen, Font: TCanvasTool;
    { CamBitmap's canvas reads the camera image (TColor: red in the low byte); other
      canvases, and writing, belong to rendering. }
    property Pixels[X, Y: integer]: TColor read GetPixel write SetPixel;
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
  { SimTwo's camera image, 640 x 480: Width, Height and Canvas.Pixels read it (the last
    <camera> shell's image, scaled); its canvas's drawing raises. }
  CamBitmap: TBitmap;

function GetSolidCanvas(R, i: integer): TCanvas;
function GetObstacleCanvas(i: integer): TCanvas;
procedure SolidCanvasClear(R, i: integer);
function GetCameraPixel(X, Y: integer): TRGBAColor;

implementation

uses s2simtwo;

type
  TCameraNumbers = array[0..3] of double;
  PCameraNumbers = ^TCameraNumbers;

function CameraRGBA(X, Y: integer): TRGBAColor;
var p: PCameraNumbers;
begin
  S2SimHostCall(hGetCameraPixel, [X, Y]);
  S2SimHostNumbers(PDouble(p));
  result.Red := Round(p^[0]); result.Green := Round(p^[1]);
  result.Blue := Round(p^[2]); result.alpha := Round(p^[3]);
end;

function TCanvas.GetPixel(X, Y: integer): TColor;
var c: TRGBAColor;
begin
  if (CamBitmap = nil) or (Self <> CamBitmap.Canvas) then begin
    BelongsToRendering('TCanvas.Pixels');
    result := clNone;
    exit;
  end;
  c := CameraRGBA(X, Y);
  result := TColor(c.Red or (c.Green shl 8) or (c.Blue shl 16));
end;
procedure TCanvas.SetPixel(X, Y: integer; c: TColor); begin BelongsToRendering('TCanvas.Pixels'); end;

procedure TCanvas.TextOut(X, Y: integer; const Text: string); begin BelongsToRendering('TCanvas.TextOut'); end;
procedure TCanvas.FillRect(const R: TRect); begin BelongsToRendering('TCanvas.FillRect'); end;
procedure TCanvas.Rectangle(X1, Y1, X2, Y2: integer); begin BelongsToRendering('TCanvas.Rectangle'); end;
procedure TCanvas.Ellipse(X1, Y1, X2, Y2: integer); begin BelongsToRendering('TCanvas.Ellipse'); end;
procedure TCanvas.MoveTo(X, Y: integer); begin BelongsToRendering('TCanvas.MoveTo'); end;
procedure TCanvas.LineTo(X, Y: integer); begin BelongsToRendering('TCanvas.LineTo'); end;

function GetSolidCanvas(R, i: integer): TCanvas; begin BelongsToRendering('GetSolidCanvas'); result := nil; end;
function GetObstacleCanvas(i: integer): TCanvas; begin BelongsToRendering('GetObstacleCanvas'); result := nil; end;
procedure SolidCanvasClear(R, i: integer); begin BelongsToRendering('SolidCanvasClear'); end;
function GetCameraPixel(X, Y: integer): TRGBAColor; begin result := CameraRGBA(X, Y); end;

initialization
  CamBitmap := TBitmap.Create;
  CamBitmap.Canvas := TCanvas.Create;
  CamBitmap.Canvas.Brush := TCanvasTool.Create;
  CamBitmap.Canvas.Pen := TCanvasTool.Create;
  CamBitmap.Canvas.Font := TCanvasTool.Create;
  CamBitmap.Width := 640;
  CamBitmap.Height := 480;
finalization
  CamBitmap.Canvas.Font.Free;
  CamBitmap.Canvas.Pen.Free;
  CamBitmap.Canvas.Brush.Free;
  CamBitmap.Canvas.Free;
  CamBitmap.Free;
end.
