{ SimTwo's canvases and camera routines (written for S2Sim after SimTwo's and Delphi's
  behaviour; no SimTwo source). A TCanvas stands in for Delphi's: its pen, brush and font are
  plain fields, sent with every drawing call to the host (plugins/pascal_script/host_canvas.cpp),
  which draws with Cairo on the canvas's image. The camera image reads (GetCameraPixel,
  CamBitmap's Width, Height and Canvas.Pixels[X, Y]) ask the host
  (plugins/pascal_script/host_camera.cpp) for the last <camera> shell's image, in SimTwo's
  640 x 480 coordinates; drawing on the camera's canvas raises "... belongs to rendering". }
unit s2simtwo_rendering;

{$mode delphi}{$H+}

interface

uses SysUtils, Types, s2simtwo_types, s2simtwo;

type
  TPenStyle = (psSolid, psDash, psDot, psDashDot, psDashDotDot, psClear, psInsideFrame);
  TBrushStyle = (bsSolid, bsClear, bsHorizontal, bsVertical, bsFDiagonal, bsBDiagonal, bsCross,
    bsDiagCross);
  TFontStyle = (fsBold, fsItalic, fsUnderline, fsStrikeOut);
  TFontStyles = set of TFontStyle;
  TPen = class
  public
    Color: TColor;
    Width: integer;
    Style: TPenStyle;
  end;
  TBrush = class
  public
    Color: TColor;
    Style: TBrushStyle;
  end;
  TFont = class
  public
    Color: TColor;
    Size: integer;
    Name: string;
    Style: TFontStyles;
  end;
  TCanvas = class
  private
    FHandle: integer;
    function Op(Code, X1, Y1, X2, Y2: integer; const Text: string): double;
    function GetPixel(X, Y: integer): TColor;
    procedure SetPixel(X, Y: integer; Value: TColor);
  public
    Pen: TPen;
    Brush: TBrush;
    Font: TFont;
    PenPos: TPoint;
    { A canvas of the host's canvas AHandle; -1 for the camera's, whose Pixels read the camera
      image (TColor: red in the low byte) and which S2Sim does not draw on. }
    constructor Create(AHandle: integer);
    destructor Destroy; override;
    procedure TextOut(X, Y: integer; const Text: string);
    function TextWidth(const Text: string): integer;
    function TextHeight(const Text: string): integer;
    procedure FillRect(const R: TRect);
    procedure Rectangle(X1, Y1, X2, Y2: integer); overload;
    procedure Rectangle(const R: TRect); overload;
    procedure Ellipse(X1, Y1, X2, Y2: integer); overload;
    procedure Ellipse(const R: TRect); overload;
    procedure MoveTo(X, Y: integer);
    procedure LineTo(X, Y: integer);
    { Fills the canvas with the brush's colour (SolidCanvasClear). }
    procedure S2SimClear;
    property Pixels[X, Y: integer]: TColor read GetPixel write SetPixel;
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

type
  TCameraNumbers = array[0..3] of double;
  PCameraNumbers = ^TCameraNumbers;

{ The last camera shell's pixel at SimTwo's (X, Y) (host_camera.cpp). }
function CameraRGBA(X, Y: integer): TRGBAColor;
var p: PCameraNumbers;
begin
  S2SimHostCall(hGetCameraPixel, [X, Y]);
  S2SimHostNumbers(PDouble(p));
  result.Red := Round(p^[0]); result.Green := Round(p^[1]);
  result.Blue := Round(p^[2]); result.alpha := Round(p^[3]);
end;

const
  { host_canvas.cpp's operations }
  opClear = 0; opRectangle = 1; opEllipse = 2; opFillRect = 3; opLine = 4; opTextOut = 5;
  opTextWidth = 6; opTextHeight = 7; opGetPixel = 8; opSetPixel = 9;

var
  Canvases: array of TCanvas;  { by the host's canvas index, made at the first use }

constructor TCanvas.Create(AHandle: integer);
begin
  inherited Create;
  FHandle := AHandle;
  Pen := TPen.Create; Pen.Color := clBlack; Pen.Width := 1; Pen.Style := psSolid;
  Brush := TBrush.Create; Brush.Color := clWhite; Brush.Style := bsSolid;
  Font := TFont.Create; Font.Color := clBlack; Font.Size := 8; Font.Name := ''; Font.Style := [];
  PenPos := Point(0, 0);
end;

destructor TCanvas.Destroy;
begin
  Font.Free; Brush.Free; Pen.Free;
  inherited Destroy;
end;

function TCanvas.Op(Code, X1, Y1, X2, Y2: integer; const Text: string): double;
begin
  if FHandle < 0 then BelongsToRendering('the camera''s TCanvas');
  result := S2SimHostCallS2(hCanvasOp, [FHandle, Code, X1, Y1, X2, Y2,
    Pen.Color, Pen.Width, Ord(Pen.Style = psClear), Brush.Color, Ord(Brush.Style = bsClear),
    Font.Color, Font.Size, Ord(fsBold in Font.Style), Ord(fsItalic in Font.Style)],
    Text, Font.Name);
end;

procedure TCanvas.TextOut(X, Y: integer; const Text: string);
begin
  PenPos := Point(X + Round(Op(opTextOut, X, Y, 0, 0, Text)), Y);
end;
function TCanvas.TextWidth(const Text: string): integer; begin result := Round(Op(opTextWidth, 0, 0, 0, 0, Text)); end;
function TCanvas.TextHeight(const Text: string): integer; begin result := Round(Op(opTextHeight, 0, 0, 0, 0, Text)); end;
procedure TCanvas.FillRect(const R: TRect); begin Op(opFillRect, R.Left, R.Top, R.Right, R.Bottom, ''); end;
procedure TCanvas.Rectangle(X1, Y1, X2, Y2: integer); begin Op(opRectangle, X1, Y1, X2, Y2, ''); end;
procedure TCanvas.Rectangle(const R: TRect); begin Op(opRectangle, R.Left, R.Top, R.Right, R.Bottom, ''); end;
procedure TCanvas.Ellipse(X1, Y1, X2, Y2: integer); begin Op(opEllipse, X1, Y1, X2, Y2, ''); end;
procedure TCanvas.Ellipse(const R: TRect); begin Op(opEllipse, R.Left, R.Top, R.Right, R.Bottom, ''); end;
procedure TCanvas.MoveTo(X, Y: integer); begin PenPos := Point(X, Y); end;
procedure TCanvas.LineTo(X, Y: integer);
begin
  Op(opLine, PenPos.X, PenPos.Y, X, Y, '');
  PenPos := Point(X, Y);
end;
procedure TCanvas.S2SimClear; begin Op(opClear, 0, 0, 0, 0, ''); end;
function TCanvas.GetPixel(X, Y: integer): TColor;
var c: TRGBAColor;
begin
  if FHandle >= 0 then begin
    result := Round(Op(opGetPixel, X, Y, 0, 0, ''));
    exit;
  end;
  c := CameraRGBA(X, Y);
  result := TColor(c.Red or (c.Green shl 8) or (c.Blue shl 16));
end;
procedure TCanvas.SetPixel(X, Y: integer; Value: TColor); begin Op(opSetPixel, X, Y, Value, 0, ''); end;

{ The host's canvas h (its TCanvas, made once, keeps its pen, brush and font), nil for -1. }
function CanvasOfHandle(h: integer): TCanvas;
begin
  result := nil;
  if h < 0 then exit;
  if h >= Length(Canvases) then SetLength(Canvases, h + 1);
  if Canvases[h] = nil then Canvases[h] := TCanvas.Create(h);
  result := Canvases[h];
end;

function GetSolidCanvas(R, i: integer): TCanvas;
begin
  result := CanvasOfHandle(Round(S2SimHostCall(hCanvasOf, [0, R, i])));
end;
function GetObstacleCanvas(i: integer): TCanvas;
begin
  result := CanvasOfHandle(Round(S2SimHostCall(hCanvasOf, [1, i, 0])));
end;
procedure SolidCanvasClear(R, i: integer);
var c: TCanvas;
begin
  c := GetSolidCanvas(R, i);
  if c = nil then
    raise EScriptHostError.Create('SolidCanvasClear: solid ' + IntToStr(i) + ' of robot ' +
      IntToStr(R) + ' has no canvas (<canvas width heigth>)');
  c.S2SimClear;
end;
function GetCameraPixel(X, Y: integer): TRGBAColor; begin result := CameraRGBA(X, Y); end;

var k: integer;

initialization
  CamBitmap := TBitmap.Create;
  CamBitmap.Canvas := TCanvas.Create(-1);
  CamBitmap.Width := 640;
  CamBitmap.Height := 480;
finalization
  for k := 0 to High(Canvases) do Canvases[k].Free;
  CamBitmap.Canvas.Free;
  CamBitmap.Free;
end.
