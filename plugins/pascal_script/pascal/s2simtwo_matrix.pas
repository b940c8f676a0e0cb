{ SimTwo's Matrix type and its dynmatrix routines (written for S2Sim after SimTwo's
  documented behaviour; no SimTwo source): row-major, element (r, c) at data[c + r * cols],
  the errors SimTwo's scripts see ("Invalid (row,col) value...", "Singular matrix..."). }
unit s2simtwo_matrix;

{$mode delphi}{$H+}

interface

uses SysUtils, Classes, Math;

type
  Matrix = record
    data: array of double;
    rows, cols: Longword;
  end;

function Mzeros(r, c: Longword): Matrix;
function Meye(n: Longword): Matrix;
function Minc(r, c: Longword): Matrix;
procedure MSetSize(var M: Matrix; r, c: Longword);
procedure Msetv(var M: Matrix; r, c: Longword; v: double);
function Mgetv(const M: Matrix; r, c: Longword): double;
procedure MUsetv(var M: Matrix; r, c: Longword; v: double);
function MUgetv(const M: Matrix; r, c: Longword): double;
function MNumRows(const M: Matrix): Longword;
function MNumCols(const M: Matrix): Longword;
function Madd(const A, B: Matrix): Matrix;
function Msub(const A, B: Matrix): Matrix;
function Mmult(const A, B: Matrix): Matrix;
function MmultReal(const A: Matrix; k: double): Matrix;
function MaddReal(const A: Matrix; k: double): Matrix;
function MsubReal(const A: Matrix; k: double): Matrix;
function Mneg(const A: Matrix): Matrix;
function Mtran(const A: Matrix): Matrix;
function Minv(const A: Matrix): Matrix;
function MOneCol(const A: Matrix; c: Longword): Matrix;
function MOneRow(const A: Matrix; r: Longword): Matrix;
function Mmin(const A: Matrix): double;
function Mmax(const A: Matrix): double;
function MmaxAbs(const A: Matrix): double;

procedure MInit(var Mat: Matrix; newrows, newcols: Longword);
procedure MTestData(const Mat: Matrix; out NRows, NCols: Longword);
function MIsGood(const Mat: Matrix): boolean;
function Mrandom(numrows, numcols: LongWord): Matrix;
procedure ArrayToMatrix(var M: Matrix; const D: array of double);
function MPower(const M: Matrix; const n: integer): Matrix;
function Minv_fast(const M: Matrix): Matrix;
function MelementMult(const A, B: Matrix): Matrix;
function MallNorm(const M: Matrix): double;
function MHflip(const M: Matrix): Matrix;
function MConv(const A, B: Matrix): Matrix;
function MCrop(const M: Matrix; uprow, leftcol, downrow, rightcol: Longword): Matrix;
function MStamp(const M, S: Matrix; drow, dcol: Longword): Matrix;
function MStampCol(const M, S: Matrix; col: Longword): Matrix;
function MStampRow(const M, S: Matrix; row: Longword): Matrix;
function MColsum(const M: Matrix): Matrix;
function MRowsum(const M: Matrix): Matrix;
function Mload(const fname: string): Matrix;
procedure Msave(M: Matrix; const fname: string);

implementation

{ --- Matrix: row-major, element (r, c) at data[c + r * cols] --- }

procedure MatrixError(const msg: string);
begin
  raise Exception.Create(msg);
end;

procedure MSetSize(var M: Matrix; r, c: Longword);
begin
  M.rows := r; M.cols := c;
  SetLength(M.data, r * c);
end;

function Mzeros(r, c: Longword): Matrix;
var i: integer;
begin
  MSetSize(result, r, c);
  for i := 0 to High(result.data) do result.data[i] := 0;
end;

function Meye(n: Longword): Matrix;
var i: Longword;
begin
  result := Mzeros(n, n);
  if n > 0 then for i := 0 to n - 1 do result.data[i + i * n] := 1;
end;

function Minc(r, c: Longword): Matrix;
var i: integer;
begin
  MSetSize(result, r, c);
  for i := 0 to High(result.data) do result.data[i] := i;
end;

function BadElement(const M: Matrix; r, c: Longword): string;
begin
  result := SysUtils.Format('Invalid (row,col) value. Matrix is (%d,%d), element required is (%d,%d)',
    [M.rows, M.cols, r, c]);
end;

procedure Msetv(var M: Matrix; r, c: Longword; v: double);
begin
  if (r >= M.rows) or (c >= M.cols) then MatrixError(BadElement(M, r, c));
  SetLength(M.data, Length(M.data));  { unshare before writing: value semantics }
  M.data[c + r * M.cols] := v;
end;

function Mgetv(const M: Matrix; r, c: Longword): double;
begin
  if (r >= M.rows) or (c >= M.cols) then MatrixError(BadElement(M, r, c));
  result := M.data[c + r * M.cols];
end;

procedure MUsetv(var M: Matrix; r, c: Longword; v: double);
begin
  if (r >= M.rows) or (c >= M.cols) then exit;
  SetLength(M.data, Length(M.data));
  M.data[c + r * M.cols] := v;
end;

function MUgetv(const M: Matrix; r, c: Longword): double;
begin
  if (r >= M.rows) or (c >= M.cols) then result := 0
  else result := M.data[c + r * M.cols];
end;

function MNumRows(const M: Matrix): Longword; begin result := M.rows; end;
function MNumCols(const M: Matrix): Longword; begin result := M.cols; end;

function Madd(const A, B: Matrix): Matrix;
var i: integer;
begin
  if (A.rows <> B.rows) or (A.cols <> B.cols) then
    MatrixError(SysUtils.Format('Cannot add matrix (%d,%d) with matrix (%d,%d)', [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] + B.data[i];
end;

function Msub(const A, B: Matrix): Matrix;
var i: integer;
begin
  if (A.rows <> B.rows) or (A.cols <> B.cols) then
    MatrixError(SysUtils.Format('Cannot subtract matrix (%d,%d) with matrix (%d,%d)', [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] - B.data[i];
end;

function Mmult(const A, B: Matrix): Matrix;
var r, c, k: Longword; s: double;
begin
  if A.cols <> B.rows then
    MatrixError(SysUtils.Format('Cannot multiply matrix (%d,%d) with matrix (%d,%d)', [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, B.cols);
  if (A.rows = 0) or (B.cols = 0) then exit;
  for r := 0 to A.rows - 1 do
    for c := 0 to B.cols - 1 do begin
      s := 0;
      if A.cols > 0 then
        for k := 0 to A.cols - 1 do s := s + A.data[k + r * A.cols] * B.data[c + k * B.cols];
      result.data[c + r * B.cols] := s;
    end;
end;

function MmultReal(const A: Matrix; k: double): Matrix;
var i: integer;
begin
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] * k;
end;

function MaddReal(const A: Matrix; k: double): Matrix;
var i: integer;
begin
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] + k;
end;

function MsubReal(const A: Matrix; k: double): Matrix;
var i: integer;
begin
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(A.data) do result.data[i] := A.data[i] - k;
end;

function Mneg(const A: Matrix): Matrix; begin result := MmultReal(A, -1); end;

function Mtran(const A: Matrix): Matrix;
var r, c: Longword;
begin
  MSetSize(result, A.cols, A.rows);
  if (A.rows = 0) or (A.cols = 0) then exit;
  for r := 0 to A.rows - 1 do
    for c := 0 to A.cols - 1 do result.data[r + c * A.rows] := A.data[c + r * A.cols];
end;

{ Gauss-Jordan with full pivoting. }
function Minv(const A: Matrix): Matrix;
var n, i, j, k, pr, pc: integer; big, t: double;
    a2: array of double; rowp, colp: array of integer; piv: array of boolean;
begin
  if A.rows <> A.cols then MatrixError('Cannot invert non-square matrix');
  n := A.rows;
  SetLength(a2, n * n);
  for i := 0 to n * n - 1 do a2[i] := A.data[i];
  SetLength(rowp, n); SetLength(colp, n); SetLength(piv, n);
  for i := 0 to n - 1 do piv[i] := false;
  for i := 0 to n - 1 do begin
    big := 0; pr := 0; pc := 0;
    for j := 0 to n - 1 do
      if not piv[j] then
        for k := 0 to n - 1 do
          if (not piv[k]) and (abs(a2[k + j * n]) >= big) then begin
            big := abs(a2[k + j * n]); pr := j; pc := k;
          end;
    piv[pc] := true;
    if pr <> pc then
      for k := 0 to n - 1 do begin
        t := a2[k + pr * n]; a2[k + pr * n] := a2[k + pc * n]; a2[k + pc * n] := t;
      end;
    rowp[i] := pr; colp[i] := pc;
    if a2[pc + pc * n] = 0 then MatrixError('Singular matrix: Pivot is 0');
    t := 1 / a2[pc + pc * n];
    a2[pc + pc * n] := 1;
    for k := 0 to n - 1 do a2[k + pc * n] := a2[k + pc * n] * t;
    for j := 0 to n - 1 do
      if j <> pc then begin
        t := a2[pc + j * n];
        a2[pc + j * n] := 0;
        for k := 0 to n - 1 do a2[k + j * n] := a2[k + j * n] - a2[k + pc * n] * t;
      end;
  end;
  for i := n - 1 downto 0 do
    if rowp[i] <> colp[i] then
      for j := 0 to n - 1 do begin
        t := a2[rowp[i] + j * n]; a2[rowp[i] + j * n] := a2[colp[i] + j * n]; a2[colp[i] + j * n] := t;
      end;
  MSetSize(result, n, n);
  for i := 0 to n * n - 1 do result.data[i] := a2[i];
end;

function MOneCol(const A: Matrix; c: Longword): Matrix;
var r: Longword;
begin
  if c >= A.cols then MatrixError(BadElement(A, 0, c));
  MSetSize(result, A.rows, 1);
  if A.rows > 0 then for r := 0 to A.rows - 1 do result.data[r] := A.data[c + r * A.cols];
end;

function MOneRow(const A: Matrix; r: Longword): Matrix;
var c: Longword;
begin
  if r >= A.rows then MatrixError(BadElement(A, r, 0));
  MSetSize(result, 1, A.cols);
  if A.cols > 0 then for c := 0 to A.cols - 1 do result.data[c] := A.data[c + r * A.cols];
end;

function Mmin(const A: Matrix): double;
var i: integer;
begin
  result := A.data[0];
  for i := 1 to High(A.data) do if A.data[i] < result then result := A.data[i];
end;

function Mmax(const A: Matrix): double;
var i: integer;
begin
  result := A.data[0];
  for i := 1 to High(A.data) do if A.data[i] > result then result := A.data[i];
end;

function MmaxAbs(const A: Matrix): double;
var i: integer;
begin
  result := abs(A.data[0]);
  for i := 1 to High(A.data) do if abs(A.data[i]) > result then result := abs(A.data[i]);
end;

procedure MInit(var Mat: Matrix; newrows, newcols: Longword);
begin
  Mat := Mzeros(newrows, newcols);
end;

procedure MTestData(const Mat: Matrix; out NRows, NCols: Longword);
begin
  NRows := Mat.rows;
  NCols := Mat.cols;
  if Mat.data = nil then MatrixError('Invalid matrix: nil data');
  if Mat.rows = 0 then MatrixError('Invalid number of rows:0');
  if Mat.cols = 0 then MatrixError('Invalid number of columns:0');
  if Longword(Length(Mat.data)) <> Mat.rows * Mat.cols then
    MatrixError('Invalid matrix: incompatible data size');
end;

{ Rows, columns and as many numbers as they say. SimTwo compares the length with a byte
  count left from an older string-based Matrix, so it says false for every matrix. }
function MIsGood(const Mat: Matrix): boolean;
begin
  result := (Mat.data <> nil) and (Mat.rows > 0) and (Mat.cols > 0) and
            (Longword(Length(Mat.data)) = Mat.rows * Mat.cols);
end;

function Mrandom(numrows, numcols: LongWord): Matrix;
var i: integer;
begin
  MSetSize(result, numrows, numcols);
  for i := 0 to High(result.data) do result.data[i] := System.Random;
end;

procedure ArrayToMatrix(var M: Matrix; const D: array of double);
var i: integer;
begin
  if M.rows * M.cols <> Longword(Length(D)) then
    MatrixError('Const Array size does not match Matrix size');
  SetLength(M.data, Length(D));  { unique }
  for i := 0 to High(D) do M.data[i] := D[i];
end;

{ By squaring; a negative power is the inverse's; power 0 the identity of M's size. }
function MPower(const M: Matrix; const n: integer): Matrix;
var P: Matrix; e: integer;
begin
  if M.rows <> M.cols then MatrixError('Cannot raise a non-square matrix to a power');
  if n < 0 then begin result := MPower(Minv(M), -n); exit; end;
  result := Meye(M.rows);
  P := M;
  e := n;
  while e > 0 do begin
    if (e and 1) <> 0 then result := Mmult(result, P);
    e := e shr 1;
    if e > 0 then P := Mmult(P, P);
  end;
end;

{ Gauss-Jordan with partial pivoting; a pivot below 1e-10 is singular. }
function Minv_fast(const M: Matrix): Matrix;
var n, c, r, k, piv: integer; a: array of double; t, p: double;
begin
  if M.rows <> M.cols then MatrixError('Cannot invert non-square matrix');
  n := M.rows;
  SetLength(a, n * n);
  for k := 0 to n * n - 1 do a[k] := M.data[k];
  result := Meye(n);
  for c := 0 to n - 1 do begin
    piv := c;
    for r := c + 1 to n - 1 do
      if abs(a[c + r * n]) > abs(a[c + piv * n]) then piv := r;
    p := a[c + piv * n];
    if abs(p) < 1e-10 then MatrixError('Singular matrix: Pivot is ' + FloatToStr(p));
    if piv <> c then
      for k := 0 to n - 1 do begin
        t := a[k + c * n]; a[k + c * n] := a[k + piv * n]; a[k + piv * n] := t;
        t := result.data[k + c * n]; result.data[k + c * n] := result.data[k + piv * n];
        result.data[k + piv * n] := t;
      end;
    for k := 0 to n - 1 do begin
      a[k + c * n] := a[k + c * n] / p;
      result.data[k + c * n] := result.data[k + c * n] / p;
    end;
    for r := 0 to n - 1 do
      if r <> c then begin
        t := a[c + r * n];
        if t <> 0 then
          for k := 0 to n - 1 do begin
            a[k + r * n] := a[k + r * n] - t * a[k + c * n];
            result.data[k + r * n] := result.data[k + r * n] - t * result.data[k + c * n];
          end;
      end;
  end;
end;

function MelementMult(const A, B: Matrix): Matrix;
var i: integer;
begin
  if (A.rows <> B.rows) or (A.cols <> B.cols) then
    MatrixError(SysUtils.Format('Cannot Element-wise mutiply matrix (%d,%d) with matrix (%d,%d)',
      [A.rows, A.cols, B.rows, B.cols]));
  MSetSize(result, A.rows, A.cols);
  for i := 0 to High(result.data) do result.data[i] := A.data[i] * B.data[i];
end;

{ The square root of the sum of every element's square (the Frobenius norm). }
function MallNorm(const M: Matrix): double;
var i: integer;
begin
  result := 0;
  for i := 0 to High(M.data) do result := result + M.data[i] * M.data[i];
  result := sqrt(result);
end;

function MHflip(const M: Matrix): Matrix;
var r, c: Longword;
begin
  MSetSize(result, M.rows, M.cols);
  if (M.rows = 0) or (M.cols = 0) then exit;
  for r := 0 to M.rows - 1 do
    for c := 0 to M.cols - 1 do
      result.data[c + r * M.cols] := M.data[(M.cols - 1 - c) + r * M.cols];
end;

{ Row by row: every row of A convolved with every row of B, in row ar * B.rows + br. }
function MConv(const A, B: Matrix): Matrix;
var ar, br, d, i, row, w: integer;
begin
  if (A.cols = 0) or (B.cols = 0) then MatrixError('Cannot convolve an empty matrix');
  result := Mzeros(A.rows * B.rows, A.cols + B.cols - 1);
  w := integer(result.cols);
  for ar := 0 to integer(A.rows) - 1 do
    for br := 0 to integer(B.rows) - 1 do begin
      row := ar * integer(B.rows) + br;
      for d := 0 to integer(A.cols) - 1 do
        for i := 0 to integer(B.cols) - 1 do
          result.data[d + i + row * w] := result.data[d + i + row * w] +
            A.data[d + ar * integer(A.cols)] * B.data[i + br * integer(B.cols)];
    end;
end;

function MCrop(const M: Matrix; uprow, leftcol, downrow, rightcol: Longword): Matrix;
var r, c: Longword;
begin
  if (downrow < uprow) or (rightcol < leftcol) then
    MatrixError('Invalid number of rows/cols:' + IntToStr(Int64(downrow) - uprow + 1) + '/' +
      IntToStr(Int64(rightcol) - leftcol + 1));
  if (downrow >= M.rows) or (rightcol >= M.cols) then
    MatrixError('Invalid number of rows/cols:' + IntToStr(downrow) + '/' + IntToStr(rightcol));
  MSetSize(result, downrow - uprow + 1, rightcol - leftcol + 1);
  for r := 0 to result.rows - 1 do
    for c := 0 to result.cols - 1 do
      result.data[c + r * result.cols] := M.data[c + leftcol + (r + uprow) * M.cols];
end;

function MStamp(const M, S: Matrix; drow, dcol: Longword): Matrix;
var r, c: Longword;
begin
  if (drow + S.rows > M.rows) or (dcol + S.cols > M.cols) then
    MatrixError(SysUtils.Format('Matrix(%d,%d) does not fit im matrix(%d,%d)!',
      [S.rows, S.cols, M.rows, M.cols]));
  result := M;
  SetLength(result.data, Length(M.data));  { unique }
  if (S.rows = 0) or (S.cols = 0) then exit;
  for r := 0 to S.rows - 1 do
    for c := 0 to S.cols - 1 do
      result.data[c + dcol + (r + drow) * M.cols] := S.data[c + r * S.cols];
end;

function MStampCol(const M, S: Matrix; col: Longword): Matrix;
begin
  result := MStamp(M, S, 0, col);
end;

function MStampRow(const M, S: Matrix; row: Longword): Matrix;
begin
  result := MStamp(M, S, row, 0);
end;

function MColsum(const M: Matrix): Matrix;
var r, c: Longword;
begin
  result := Mzeros(1, M.cols);
  if (M.rows = 0) or (M.cols = 0) then exit;
  for r := 0 to M.rows - 1 do
    for c := 0 to M.cols - 1 do result.data[c] := result.data[c] + M.data[c + r * M.cols];
end;

function MRowsum(const M: Matrix): Matrix;
var r, c: Longword;
begin
  result := Mzeros(M.rows, 1);
  if (M.rows = 0) or (M.cols = 0) then exit;
  for r := 0 to M.rows - 1 do
    for c := 0 to M.cols - 1 do result.data[r] := result.data[r] + M.data[c + r * M.cols];
end;

{ A text file, one row a line, numbers separated by blanks, every row as long as the first. }
function Mload(const fname: string): Matrix;
var lines, parts: TStringList; r, c, cols: integer; line: string;
begin
  lines := TStringList.Create;
  parts := TStringList.Create;
  try
    try
      lines.LoadFromFile(fname);
    except
      on E: Exception do MatrixError('Mload: cannot read ' + fname + ': ' + E.Message);
    end;
    while (lines.Count > 0) and (Trim(lines[lines.Count - 1]) = '') do lines.Delete(lines.Count - 1);
    cols := -1;
    result := Mzeros(0, 0);
    for r := 0 to lines.Count - 1 do begin
      line := StringReplace(Trim(lines[r]), #9, ' ', [rfReplaceAll]);
      parts.Clear;
      ExtractStrings([' '], [], PChar(line), parts);
      if cols < 0 then begin
        cols := parts.Count;
        if cols = 0 then MatrixError('Bad file format: cannot load matrix');
        result := Mzeros(lines.Count, cols);
      end;
      if parts.Count <> cols then MatrixError('Bad file format: cannot load matrix');
      for c := 0 to cols - 1 do result.data[c + r * cols] := StrToFloat(parts[c]);
    end;
    if cols < 0 then MatrixError('Bad file format: cannot load matrix');
  finally
    parts.Free;
    lines.Free;
  end;
end;

{ Every element (SimTwo's column loop runs to the row count: a non-square matrix is written
  short or raises there), 17 digits, CR LF after each row. }
procedure Msave(M: Matrix; const fname: string);
var f: TextFile; r, c: Longword;
begin
  AssignFile(f, fname);
  {$I-} Rewrite(f); {$I+}
  if IOResult <> 0 then MatrixError('Msave: cannot write ' + fname);
  try
    if (M.rows > 0) and (M.cols > 0) then
      for r := 0 to M.rows - 1 do begin
        for c := 0 to M.cols - 1 do Write(f, SysUtils.Format('%.17g ', [M.data[c + r * M.cols]]));
        Write(f, #13#10);
      end;
  finally
    CloseFile(f);
  end;
end;

end.
