# mutate-sites.awk -- lists every mutation site of the C files it reads, for
# scripts/mutate.  One site per output line, tab-separated:
#     file  line  column  old  new  k  code  function
# where `old` is the exact text at line:column, `new` its replacement, k the
# ordinal of `old` among the sites of that line that have the same old->new,
# `code` the source line with runs of blanks squeezed (followed by " [n]"
# on the n-th line of its function that reads the same) and `function` the
# function (or file-level declaration) it is in; "file, function, old->new
# #k, code" names a site without its line number.
#
# Operators (the classic single-token set of Offutt et al., 1996):
#   relational  <  <=  >  >=  ==  !=   each flipped to its partner
#               (< <-> <=, > <-> >=, == <-> !=)
#   arithmetic  + -> -, - -> +, += <-> -=   (not ++ -- -> or exponents)
#   literal     0 -> 1, 1 -> 0, 1 -> 2, 2 -> 1   (also 1.0, 2u, 0.0f ...)
#   statement   `break;` and `continue;` deleted; an early `return ...;`
#               (one nested deeper than the function body, or after an
#               `if (...)` on its line) deleted.
# Never mutated: comments, string and character literals, preprocessor
# lines and their continuations, assertions (g_assert*, g_return*_if_fail,
# static asserts: they only report bugs, they compute nothing), and files
# marked GENERATED in their first lines (data tables).
# Cost: linear in the size of the sources.
BEGIN { FS = "\n" }

FNR == 1 { incom = 0; cont = 0; adepth = 0; skipfile = 0; fn = "-" }
FNR <= 3 && /GENERATED/ { skipfile = 1 }
skipfile { next }

{
    line = $0
    gsub(/\t/, " ", line)
    m = mask(line)
    if (cont || m ~ /^ *#/) { cont = (line ~ /\\$/); next }
    if (adepth > 0) { adepth += balance(m, 1); next }
    if (m ~ /^[A-Za-z_]/ && match(m, /[A-Za-z_][A-Za-z0-9_]* *\(/))
        fn = substr(m, RSTART, RLENGTH)
    else if (m ~ /^[A-Za-z_]/ && match(m, /[A-Za-z_][A-Za-z0-9_]*( *\[[^]]*\])* *=/))
        fn = substr(m, RSTART, RLENGTH)
    sub(/ *[(=\[].*$/, "", fn)
    if (match(m, /(g_assert|g_return_val_if_fail|g_return_if_fail|static_assert|_Static_assert|G_STATIC_ASSERT)/)) {
        adepth = balance(m, RSTART)
        next
    }
    scan(FILENAME, FNR, line, m)
}

# Parentheses opened minus closed in m from position `from` on.
function balance(m, from,    i, c, d) {
    d = 0
    for (i = from; i <= length(m); i++) {
        c = substr(m, i, 1)
        if (c == "(") d++
        else if (c == ")") d--
    }
    return d
}

# The line with comments, string and character literals blanked out
# (columns kept); `incom` carries an open /* comment to the next line.
function mask(s,    out, i, n, c, q) {
    out = ""; n = length(s); i = 1
    while (i <= n) {
        c = substr(s, i, 1)
        if (incom) {
            if (c == "*" && substr(s, i + 1, 1) == "/") { incom = 0; out = out "  "; i += 2 }
            else { out = out " "; i++ }
            continue
        }
        if (c == "/" && substr(s, i + 1, 1) == "*") { incom = 1; out = out "  "; i += 2; continue }
        if (c == "/" && substr(s, i + 1, 1) == "/") { for (; i <= n; i++) out = out " "; break }
        if (c == "\"" || c == "'") {
            q = c; out = out " "; i++
            while (i <= n) {
                c = substr(s, i, 1)
                if (c == "\\") { out = out "  "; i += 2; continue }
                out = out " "; i++
                if (c == q) break
            }
            continue
        }
        out = out c; i++
    }
    return out
}

function emit(f, ln, col, old, new, code,    key) {
    key = f SUBSEP ln SUBSEP old SUBSEP new
    nth[key]++
    printf "%s\t%d\t%d\t%s\t%s\t%d\t%s\t%s\n", f, ln, col, old, new, nth[key],
        code, fn
}

# True when the + or - at i is the sign of a floating exponent (1e-5).
function exponent(m, i,    j, p) {
    p = substr(m, i - 1, 1)
    if (p != "e" && p != "E") return 0
    for (j = i - 2; j >= 1 && substr(m, j, 1) ~ /[0-9.]/; j--) ;
    if (j == i - 2) return 0
    return j < 1 || substr(m, j, 1) !~ /[A-Za-z_]/
}

function scan(f, ln, line, m,    code, n, i, c, p, x, tok, semi, ind) {
    code = line
    gsub(/  +/, " ", code); sub(/^ /, "", code); sub(/ $/, "", code)
    # the n-th line of a function that reads like an earlier one is named
    # "code [n]", so that equal lines (the 0, of a table) stay apart
    if (++same[f, fn, code] > 1) code = code " [" same[f, fn, code] "]"
    n = length(m)
    match(m, /^ */); ind = RLENGTH
    for (i = 1; i <= n; i++) {
        c = substr(m, i, 1); p = substr(m, i - 1, 1); x = substr(m, i + 1, 1)
        if (c == "<" || c == ">") {
            if (p == c || x == c || (c == ">" && p == "-")) continue
            if (x == "=") { emit(f, ln, i, c "=", c, code); i++ }
            else emit(f, ln, i, c, c "=", code)
        } else if ((c == "=" || c == "!") && x == "=") {
            emit(f, ln, i, c "=", (c == "=" ? "!" : "=") "=", code); i++
        } else if (c == "+" || c == "-") {
            if (p == c || x == c || (c == "-" && x == ">")) { i++; continue }
            if (exponent(m, i)) continue
            if (x == "=") { emit(f, ln, i, c "=", (c == "+" ? "-" : "+") "=", code); i++ }
            else emit(f, ln, i, c, (c == "+" ? "-" : "+"), code)
        } else if (c ~ /[0-9]/ && p !~ /[A-Za-z0-9_.]/) {
            match(substr(m, i), /^[0-9][0-9A-Za-z_.]*/)
            tok = substr(m, i, RLENGTH)
            literal(f, ln, i, tok, code)
            i += RLENGTH - 1
        } else if (c ~ /[A-Za-z_]/ && p !~ /[A-Za-z0-9_]/) {
            match(substr(m, i), /^[A-Za-z_][A-Za-z0-9_]*/)
            tok = substr(m, i, RLENGTH)
            semi = index(substr(m, i), ";")
            if ((tok == "break" || tok == "continue") && substr(m, i + RLENGTH) ~ /^ *;/)
                emit(f, ln, i, substr(line, i, semi), ";", code)
            else if (tok == "return" && semi > 0 &&
                     (ind >= 8 || substr(m, 1, i - 1) ~ /\) *$|else *$/))
                emit(f, ln, i, substr(line, i, semi), ";", code)
            i += RLENGTH - 1
        }
    }
}

# 0/1/2 literals, with an optional fraction of zeros and a suffix.
function literal(f, ln, i, tok, code,    d, rest) {
    if (tok !~ /^[012](\.0*)?[fFuUlL]*$/) return
    d = substr(tok, 1, 1); rest = substr(tok, 2)
    if (d == "0") emit(f, ln, i, tok, "1" rest, code)
    if (d == "1") { emit(f, ln, i, tok, "0" rest, code); emit(f, ln, i, tok, "2" rest, code) }
    if (d == "2") emit(f, ln, i, tok, "1" rest, code)
}
