// Draws on the board's canvas and the sign's once (docs/scripting.md, "Canvases"), then prints
// what Pixels reads back. The tests (tests/plugins/pascal_script/script_canvas_test.cpp,
// tests/apps/render/canvas_texture_test.cpp) check the pixels.
var
  drawn: boolean;

procedure Control;
var
  c: TCanvas;
begin
  if drawn then exit;
  drawn := true;
  c := GetSolidCanvas(0, 0);
  // A red rectangle with a blue outline over x 20..79, y 20..59.
  c.Pen.Color := clBlue;
  c.Brush.Color := clRed;
  c.Rectangle(20, 20, 80, 60);
  // Black text on yellow from (100, 20).
  c.Brush.Color := clYellow;
  c.Font.Color := clBlack;
  c.Font.Size := 14;
  c.TextOut(100, 20, 'S2Sim');
  // A green line, an outlined circle and a lime pixel.
  c.Pen.Color := clGreen;
  c.Pen.Width := 3;
  c.MoveTo(20, 120);
  c.LineTo(180, 120);
  c.Pen.Width := 1;
  c.Pen.Color := clBlack;
  c.Brush.Style := bsClear;
  c.Ellipse(120, 70, 160, 110);
  c.Pixels[5, 5] := clLime;
  WriteLn('PIXEL ' + IntToStr(c.Pixels[50, 40]) + ' ' + IntToStr(c.Pixels[5, 5]) + ' ' +
    IntToStr(c.Pixels[199, 149]) + ' ' + IntToStr(c.Pixels[200, 0]));
  WriteLn('TEXT ' + IntToStr(c.TextWidth('S2Sim')) + ' ' + IntToStr(c.TextHeight('S2Sim')));
  // The sign: cleared to navy, a white filled ellipse.
  c := GetObstacleCanvas(0);
  c.Brush.Color := clNavy;
  c.FillRect(Rect(0, 0, 150, 100));
  c.Brush.Color := clWhite;
  c.Pen.Style := psClear;
  c.Ellipse(25, 10, 125, 90);
  c.Font.Size := 16;
  c.Brush.Style := bsClear;
  c.Font.Color := clRed;
  c.TextOut(38, 38, 'SimTwo');
end;

procedure Initialize;
begin
  drawn := false;
end;
