{ SimTwo's constants and record types for scripts (same layouts as SimTwo's), and the named
  errors of what S2Sim does not have yet (written for S2Sim; no SimTwo source). }
unit s2simtwo_types;

{$mode delphi}{$H+}

interface

uses SysUtils;

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
  { The spray-painting routines' (s2simtwo_paint). }
  TPaintVisuals = (pmPaint, pmHeatmap, pmResult);
  TFace = record
    vertice0, vertice1, vertice2, center, normal: TPoint3D;
    area: double;
    neighbors: array of integer;
  end;
  TTriangles = array of TFace;
  THistogram = record
    binUpperLimit: array of double;
    binHeight: array of integer;
  end;

  EScriptHostError = class(Exception);

{ "<routine> is not yet available in S2Sim": what S2Sim lacks raises, never a silent no-op. }
procedure NotYetAvailable(const routine: string);
{ "<routine> belongs to rendering, ...": canvas and camera. }
procedure BelongsToRendering(const routine: string);

implementation

procedure NotYetAvailable(const routine: string);
begin
  raise EScriptHostError.Create(routine + ' is not yet available in S2Sim (docs/scripting.md)');
end;

procedure BelongsToRendering(const routine: string);
begin
  raise EScriptHostError.Create(routine + ' belongs to SimTwo''s own rendering, which S2Sim does not reproduce');
end;

end.
