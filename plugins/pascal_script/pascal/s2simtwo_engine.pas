{ The Pascal Script engine's built-ins that Free Pascal lacks (written for S2Sim; no Pascal
  Script source): SimTwo scripts may call them since the engine registers them. The ones FPC
  has with the same meaning (IntToStr, Copy, Inc, Trim, Unassigned, ...) come from its RTL. }
unit s2simtwo_engine;

{$mode delphi}{$H+}

interface

uses SysUtils, Classes, Types, Variants;

type
  { Pascal Script's run-time error kinds, in its order. }
  TIFException = (ErNoError, erCannotImport, erInvalidType, ErInternalError, erInvalidHeader,
    erInvalidOpcode, erInvalidOpcodeParameter, erNoMainProc, erOutOfGlobalVarsRange,
    erOutOfProcRange, ErOutOfRange, erOutOfStackRange, ErTypeMismatch, erUnexpectedEof,
    erVersionError, ErDivideByZero, ErMathError, erCouldNotCallProc, erOutofRecordRange,
    erOutOfMemory, erException, erNullPointerException, erNullVariantError,
    erInterfaceNotSupported, erCustomError);

  { RaiseException's exception: its kind and its parameter. }
  EScriptException = class(Exception)
  public
    Kind: TIFException;
    Param: string;
  end;

  { Menu types, for scripts that name them: a script has no form here (NewMenu raises). }
  TPopupAlignment = (paLeft, paRight, paCenter);
  TMenuItem = class(TComponent);
  TMainMenu = class(TComponent);
  TPopupMenu = class(TComponent);

function StrGet(const S: string; I: LongInt): Char;
function StrGet2(const S: string; I: LongInt): Char;
procedure StrSet(C: Char; I: LongInt; var S: string);
function WStrGet(const S: WideString; I: LongInt): WideChar;
procedure WStrSet(C: WideChar; I: LongInt; var S: WideString);
function VarArrayGet(const S: Variant; I: LongInt): Variant;
procedure VarArraySet(var C: Variant; I: LongInt; const S: Variant);
function PadL(const S: string; I: LongInt): string;
function PadR(const S: string; I: LongInt): string;
function PadZ(const S: string; I: LongInt): string;
function Replicate(C: Char; I: LongInt): string;
function Int64ToStr(I: Int64): string;

function GetArrayLength(const A: array of double): LongInt; overload;
function GetArrayLength(const A: array of single): LongInt; overload;
function GetArrayLength(const A: array of integer): LongInt; overload;
function GetArrayLength(const A: array of Int64): LongInt; overload;
function GetArrayLength(const A: array of byte): LongInt; overload;
function GetArrayLength(const A: array of boolean): LongInt; overload;
function GetArrayLength(const A: array of string): LongInt; overload;
function GetArrayLength(const A: array of Variant): LongInt; overload;
procedure SetArrayLength(var A: TDoubleDynArray; Count: LongInt); overload;
procedure SetArrayLength(var A: TSingleDynArray; Count: LongInt); overload;
procedure SetArrayLength(var A: TIntegerDynArray; Count: LongInt); overload;
procedure SetArrayLength(var A: TInt64DynArray; Count: LongInt); overload;
procedure SetArrayLength(var A: TByteDynArray; Count: LongInt); overload;
procedure SetArrayLength(var A: TBooleanDynArray; Count: LongInt); overload;
procedure SetArrayLength(var A: TStringDynArray; Count: LongInt); overload;

procedure RaiseException(Ex: TIFException; const Param: string);
procedure RaiseLastException;
function ExceptionType: TIFException;
function ExceptionParam: string;
function ExceptionProc: LongWord;
function ExceptionPos: LongWord;
function ExceptionToString(er: TIFException; const Param: string): string;

function ShortCutToText(ShortCut: Word): string;
function TextToShortCut(Text: string): Word;

function IdispatchInvoke(Self: IDispatch; PropertySet: Boolean; const Name: string;
  const Par: array of Variant): Variant;
function NewMenu(Owner: TComponent; const AName: string; const Items: array of TMenuItem): TMainMenu;
function NewPopupMenu(Owner: TComponent; const AName: string; Alignment: TPopupAlignment;
  AutoPopup: Boolean; const Items: array of TMenuItem): TPopupMenu;
function NewSubMenu(const ACaption: string; HCTX: Word; const AName: string;
  const Items: array of TMenuItem; AEnabled: Boolean): TMenuItem;
function NewItem(const ACaption: string; AShortCut: Word; AChecked, AEnabled: Boolean;
  AOnClick: TNotifyEvent; HCTX: Word; const AName: string): TMenuItem;
function NewLine: TMenuItem;

implementation

function StrGet(const S: string; I: LongInt): Char;
begin
  if (I < 1) or (I > Length(S)) then
    raise EScriptException.Create('Out Of Range');
  result := S[I];
end;

function StrGet2(const S: string; I: LongInt): Char;
begin
  result := StrGet(S, I);
end;

procedure StrSet(C: Char; I: LongInt; var S: string);
begin
  if (I < 1) or (I > Length(S)) then
    raise EScriptException.Create('Out Of Range');
  S[I] := C;
end;

function WStrGet(const S: WideString; I: LongInt): WideChar;
begin
  if (I < 1) or (I > Length(S)) then
    raise EScriptException.Create('Out Of Range');
  result := S[I];
end;

procedure WStrSet(C: WideChar; I: LongInt; var S: WideString);
begin
  if (I < 1) or (I > Length(S)) then
    raise EScriptException.Create('Out Of Range');
  S[I] := C;
end;

function VarArrayGet(const S: Variant; I: LongInt): Variant;
begin
  result := S[I];
end;

procedure VarArraySet(var C: Variant; I: LongInt; const S: Variant);
begin
  C[I] := S;
end;

function PadL(const S: string; I: LongInt): string;
begin
  result := S;
  if Length(S) < I then result := StringOfChar(' ', I - Length(S)) + S;
end;

function PadR(const S: string; I: LongInt): string;
begin
  result := S;
  if Length(S) < I then result := S + StringOfChar(' ', I - Length(S));
end;

function PadZ(const S: string; I: LongInt): string;
begin
  result := S;
  if Length(S) < I then result := StringOfChar('0', I - Length(S)) + S;
end;

function Replicate(C: Char; I: LongInt): string;
begin
  result := StringOfChar(C, I);
end;

function Int64ToStr(I: Int64): string;
begin
  result := IntToStr(I);
end;

function GetArrayLength(const A: array of double): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of single): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of integer): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of Int64): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of byte): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of boolean): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of string): LongInt; begin result := Length(A); end;
function GetArrayLength(const A: array of Variant): LongInt; begin result := Length(A); end;
procedure SetArrayLength(var A: TDoubleDynArray; Count: LongInt); begin SetLength(A, Count); end;
procedure SetArrayLength(var A: TSingleDynArray; Count: LongInt); begin SetLength(A, Count); end;
procedure SetArrayLength(var A: TIntegerDynArray; Count: LongInt); begin SetLength(A, Count); end;
procedure SetArrayLength(var A: TInt64DynArray; Count: LongInt); begin SetLength(A, Count); end;
procedure SetArrayLength(var A: TByteDynArray; Count: LongInt); begin SetLength(A, Count); end;
procedure SetArrayLength(var A: TBooleanDynArray; Count: LongInt); begin SetLength(A, Count); end;
procedure SetArrayLength(var A: TStringDynArray; Count: LongInt); begin SetLength(A, Count); end;

{ --- exceptions: Pascal Script's kinds over FPC's exception objects --- }

function ExceptionToString(er: TIFException; const Param: string): string;
begin
  case er of
    ErNoError: result := 'No Error';
    erCannotImport: result := 'Cannot Import ' + Param;
    erInvalidType: result := 'Invalid Type';
    ErInternalError: result := 'Internal error';
    erInvalidHeader: result := 'Invalid Header';
    erInvalidOpcode: result := 'Invalid Opcode';
    erInvalidOpcodeParameter: result := 'Invalid Opcode Parameter';
    erNoMainProc: result := 'no Main Proc';
    erOutOfGlobalVarsRange: result := 'Out of Global Vars range';
    erOutOfProcRange: result := 'Out of Proc Range';
    ErOutOfRange: result := 'Out Of Range';
    erOutOfStackRange: result := 'Out Of Stack Range';
    ErTypeMismatch: result := 'Type Mismatch';
    erUnexpectedEof: result := 'Unexpected End Of File';
    erVersionError: result := 'Version error';
    ErDivideByZero: result := 'divide by Zero';
    ErMathError: result := 'Math error';
    erCouldNotCallProc: result := 'Could not call proc';
    erOutofRecordRange: result := 'Out of Record Fields Range';
    erOutOfMemory: result := 'Out Of Memory';
    erException: result := 'Exception: ' + Param;
    erNullPointerException: result := 'Null Pointer Exception';
    erNullVariantError: result := 'Null variant error';
    erInterfaceNotSupported: result := 'Interface not supported';
  else
    result := Param;  { erCustomError: the text itself }
  end;
end;

procedure RaiseException(Ex: TIFException; const Param: string);
var E: EScriptException;
begin
  E := EScriptException.Create(ExceptionToString(Ex, Param));
  E.Kind := Ex;
  E.Param := Param;
  raise E;
end;

procedure RaiseLastException;
var E: TObject;
begin
  E := ExceptObject;
  if E = nil then exit;  { as Pascal Script: nothing was raised, nothing to raise again }
  raise TObject(AcquireExceptionObject);
end;

function ExceptionType: TIFException;
var E: TObject;
begin
  E := ExceptObject;
  if E = nil then result := ErNoError
  else if E is EScriptException then result := EScriptException(E).Kind
  else if (E is EDivByZero) or (E is EZeroDivide) then result := ErDivideByZero
  else if E is ERangeError then result := ErOutOfRange
  else if E is EAccessViolation then result := erNullPointerException
  else if E is EOutOfMemory then result := erOutOfMemory
  else if E is EMathError then result := ErMathError
  else result := erException;
end;

function ExceptionParam: string;
var E: TObject;
begin
  E := ExceptObject;
  if E = nil then result := ''
  else if E is EScriptException then result := EScriptException(E).Param
  else if E is Exception then result := Exception(E).Message
  else result := E.ClassName;
end;

{ Native code has no procedure numbers or byte-code positions: the procedure is 0, the
  position the raising code address (its low 32 bits). }
function ExceptionProc: LongWord;
begin
  result := 0;
end;

function ExceptionPos: LongWord;
begin
  result := LongWord(PtrUInt(ExceptAddr) and $FFFFFFFF);
end;

{ --- shortcuts: the LCL's text for a key code with scShift $2000, scCtrl $4000, scAlt $8000 --- }

function KeyName(Key: Word): string;
begin
  case Key of
    8: result := 'BkSp'; 9: result := 'Tab'; 13: result := 'Enter'; 27: result := 'Esc';
    32: result := 'Space'; 33: result := 'PgUp'; 34: result := 'PgDn'; 35: result := 'End';
    36: result := 'Home'; 37: result := 'Left'; 38: result := 'Up'; 39: result := 'Right';
    40: result := 'Down'; 45: result := 'Ins'; 46: result := 'Del';
    48..57, 65..90: result := Chr(Key);
    112..135: result := 'F' + IntToStr(Key - 111);
  else
    result := '';
  end;
end;

function ShortCutToText(ShortCut: Word): string;
var name: string;
begin
  name := KeyName(ShortCut and $FF);
  if name = '' then begin result := ''; exit; end;
  result := '';
  if ShortCut and $2000 <> 0 then result := result + 'Shift+';
  if ShortCut and $4000 <> 0 then result := result + 'Ctrl+';
  if ShortCut and $8000 <> 0 then result := result + 'Alt+';
  result := result + name;
end;

function TextToShortCut(Text: string): Word;
var mods: Word; k: integer; rest: string;
begin
  result := 0;
  mods := 0;
  rest := Text;
  while true do begin
    if SameText(Copy(rest, 1, 6), 'Shift+') then begin mods := mods or $2000; Delete(rest, 1, 6); end
    else if SameText(Copy(rest, 1, 5), 'Ctrl+') then begin mods := mods or $4000; Delete(rest, 1, 5); end
    else if SameText(Copy(rest, 1, 4), 'Alt+') then begin mods := mods or $8000; Delete(rest, 1, 4); end
    else break;
  end;
  for k := 1 to 255 do
    if (KeyName(k) <> '') and SameText(KeyName(k), rest) then begin
      result := mods or k;
      exit;
    end;
end;

{ --- what needs Windows or a form --- }

function IdispatchInvoke(Self: IDispatch; PropertySet: Boolean; const Name: string;
  const Par: array of Variant): Variant;
begin
  raise EScriptException.Create('IdispatchInvoke: S2Sim runs on Linux, without COM automation');
end;

procedure NoForm(const routine: string);
begin
  raise EScriptException.Create(routine + ': S2Sim gives a script no form to put a menu on');
end;

function NewMenu(Owner: TComponent; const AName: string; const Items: array of TMenuItem): TMainMenu;
begin NoForm('NewMenu'); result := nil; end;
function NewPopupMenu(Owner: TComponent; const AName: string; Alignment: TPopupAlignment;
  AutoPopup: Boolean; const Items: array of TMenuItem): TPopupMenu;
begin NoForm('NewPopupMenu'); result := nil; end;
function NewSubMenu(const ACaption: string; HCTX: Word; const AName: string;
  const Items: array of TMenuItem; AEnabled: Boolean): TMenuItem;
begin NoForm('NewSubMenu'); result := nil; end;
function NewItem(const ACaption: string; AShortCut: Word; AChecked, AEnabled: Boolean;
  AOnClick: TNotifyEvent; HCTX: Word; const AName: string): TMenuItem;
begin NoForm('NewItem'); result := nil; end;
function NewLine: TMenuItem;
begin NoForm('NewLine'); result := nil; end;

end.
