// SPDX-License-Identifier: MIT
// np_vec_check - scoreboard for noisepipe golden vectors in $readmemh form
// (Icarus Verilog, iverilog -g2012). It reads, unchanged, a vector file
// written by `noisepipe vectors --format readmemh` and a result file written
// by a device (`noisepipe device --format results`, an RTL simulation, a
// board), compares every result with the expected output field, prints
// `inputs => got expected: want` for the first MAX_ERRORS mismatches, ends
// with a one-line verdict and stops with $fatal (non-zero exit status of vvp)
// on any mismatch, on a count mismatch, or when there is nothing to check.
//
// Vector word, MSB first (VEC_W = 1 + N_IN*IN_W + N_OUT*OUT_W bits; the file
// writes it as ceil(VEC_W/4) hex digits, one word per line, after '//' lines):
//
//   VEC_W-1                                                        0
//   +-------+--------+--------+-- ... --+---------+-- ... --+---------+
//   | valid | in[0]  | in[1]  |         | out[0]  |         | out[N-1]|
//   +-------+--------+--------+-- ... --+---------+-- ... --+---------+
//     1 bit   IN_W     IN_W                OUT_W              OUT_W
//
// For classic3: {1'b1, x[15:0], y[15:0], z[15:0], f[7:0]} = 57 bits, 15 digits.
// A word whose valid bit is not 1 (0, or x past the end of the file) ends the
// set. Results: per transaction, in the order of the vectors, N_OUT hex words
// of OUT_W bits, out[0] first, as the columns of one line ("f" for classic3;
// "f dfdx dfdy dfdz" for a unit with four outputs); '//' comments allowed.
//
// Plusargs: +vectors=FILE +results=FILE (defaults vectors.memh, results.hex).
// Both files are scanned first and read with an exact $readmemh range, so
// Icarus prints no "not enough words" warnings; DEPTH only bounds the
// memories. When a file's header has "// unit NAME" or "// count N" lines (as
// noisepipe writes them), NAME must be UNIT and N the number of transactions:
// a truncated or mismatched file fails even where its words look valid.
module np_vec_check #(
    parameter UNIT = "unit",  // in messages; a header's "// unit" line must name it
    parameter integer N_IN = 3,
    parameter integer IN_W = 16,
    parameter integer N_OUT = 1,
    parameter integer OUT_W = 8,
    parameter integer DEPTH = 1 << 21,
    parameter integer MAX_ERRORS = 20
);
    localparam integer RES_W = N_OUT * OUT_W;
    localparam integer VEC_W = 1 + N_IN * IN_W + RES_W;
    localparam integer POS_VALID = VEC_W - 1;
    localparam integer POS_IN0 = VEC_W - 2;  // MSB of in[0]; in[k] is [POS_IN0 - k*IN_W -: IN_W]

    reg [VEC_W-1:0] vec[0:DEPTH-1];
    reg [OUT_W-1:0] res[0:N_OUT*DEPTH-1];  // transaction i: res[N_OUT*i + j], output j

    // Scan a $readmemh file before reading it: the number of data words
    // (whitespace-separated tokens outside '//' comments, as $readmemh reads
    // them; '@addr' jumps are not words, and are not expected), and what the header
    // says: "// unit NAME" and "// count N" (hdr_count -1 and hdr_unit "" when
    // the file has no such line).
    task automatic scan(input string path, output integer words, output integer hdr_count,
                        output string hdr_unit);
        integer fd, r, n;
        string tok, name;
        reg [8*256-1:0] rest;
        begin
            words = 0;
            hdr_count = -1;
            hdr_unit = "";
            fd = $fopen(path, "r");
            if (fd == 0) $fatal(1, "%s_tb: cannot open %s", UNIT, path);
            r = $fscanf(fd, "%s", tok);
            while (r == 1) begin
                if (tok.len() >= 2 && tok.substr(0, 1) == "//") begin
                    r = $fgets(rest, fd);  // the rest of the comment line, however long
                    if (tok == "//" && $sscanf(rest, " count %d", n) == 1) hdr_count = n;
                    if (tok == "//" && $sscanf(rest, " unit %s", name) == 1) hdr_unit = name;
                    while (r > 0 && rest[7:0] != 8'h0a) r = $fgets(rest, fd);
                end else if (tok.substr(0, 0) != "@") begin
                    words = words + 1;
                end
                r = $fscanf(fd, "%s", tok);
            end
            $fclose(fd);
        end
    endtask

    string vec_path, res_path;
    string vec_unit, res_unit;
    integer n_words, n_res_words, n_res, n_vec, n_cmp, errors, i, k, vec_count, res_count;
    reg [IN_W-1:0] in_field;
    reg [OUT_W-1:0] out_field;
    reg [RES_W-1:0] want, got;

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) vec_path = "vectors.memh";
        if (!$value$plusargs("results=%s", res_path)) res_path = "results.hex";

        scan(vec_path, n_words, vec_count, vec_unit);
        scan(res_path, n_res_words, res_count, res_unit);
        if (n_res_words % N_OUT != 0)
            $fatal(1, "%s_tb: %s: %0d words is not a whole number of transactions of %0d outputs",
                   UNIT, res_path, n_res_words, N_OUT);
        n_res = n_res_words / N_OUT;
        if (vec_unit != "" && vec_unit != UNIT)
            $fatal(1, "%s_tb: %s holds vectors of unit %s", UNIT, vec_path, vec_unit);
        if (res_unit != "" && res_unit != UNIT)
            $fatal(1, "%s_tb: %s holds results of unit %s", UNIT, res_path, res_unit);
        if (n_words > DEPTH || n_res > DEPTH)
            $fatal(1, "%s_tb: %0d vector words, %0d results: more than DEPTH = %0d (recompile with -P<top>.DEPTH=N)",
                   UNIT, n_words, n_res, DEPTH);
        if (n_words > 0) $readmemh(vec_path, vec, 0, n_words - 1);
        if (n_res > 0) $readmemh(res_path, res, 0, n_res_words - 1);

        n_vec = 0;
        while (n_vec < n_words && vec[n_vec][POS_VALID] === 1'b1) n_vec = n_vec + 1;

        n_cmp = n_vec < n_res ? n_vec : n_res;
        errors = 0;
        for (i = 0; i < n_cmp; i = i + 1) begin
            want = vec[i][RES_W-1:0];
            for (k = 0; k < N_OUT; k = k + 1) got[RES_W-1-k*OUT_W-:OUT_W] = res[N_OUT*i+k];
            if (got !== want) begin
                errors = errors + 1;
                if (errors <= MAX_ERRORS) begin
                    for (k = 0; k < N_IN; k = k + 1) begin
                        in_field = vec[i][POS_IN0-k*IN_W-:IN_W];
                        $write("%h ", in_field);
                    end
                    $write("=>");
                    for (k = 0; k < N_OUT; k = k + 1) begin
                        out_field = got[RES_W-1-k*OUT_W-:OUT_W];
                        $write(" %h", out_field);
                    end
                    $write(" expected:");
                    for (k = 0; k < N_OUT; k = k + 1) begin
                        out_field = want[RES_W-1-k*OUT_W-:OUT_W];
                        $write(" %h", out_field);
                    end
                    $display("");
                end
            end
        end
        if (errors > MAX_ERRORS)
            $display("%s_tb: (only the first %0d errors are shown)", UNIT, MAX_ERRORS);

        if (n_vec == 0)
            $fatal(1, "%s_tb: no valid vectors in %s: nothing was checked", UNIT, vec_path);
        if (vec_count >= 0 && vec_count != n_vec)
            $fatal(1, "%s_tb: %s: the header's count is %0d but %0d vectors are valid",
                   UNIT, vec_path, vec_count, n_vec);
        if (res_count >= 0 && res_count != n_res)
            $fatal(1, "%s_tb: %s: the header's count is %0d but it holds %0d results",
                   UNIT, res_path, res_count, n_res);
        if (n_res != n_vec)
            $fatal(1, "%s_tb: %0d vectors but %0d results (%s); %0d errors in the first %0d",
                   UNIT, n_vec, n_res, res_path, errors, n_cmp);
        if (errors != 0)
            $fatal(1, "%s_tb: In %0d tests, %0d errors found.", UNIT, n_vec, errors);
        $display("%s_tb: In %0d tests, no errors found.", UNIT, n_vec);
        $finish;
    end
endmodule
