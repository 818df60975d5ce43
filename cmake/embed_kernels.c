/* Build-time generator for the single-source kernels.
 *
 *   embed_kernels SOURCE_OUT TABLE_OUT KERNEL_DIR file.cl...
 *
 * SOURCE_OUT: one C string, amsph_opencl_source, holding every .cl file with
 *   its local #include "..." lines expanded once each, for the OpenCL backend
 *   to build at run time (the binary then runs from any directory).
 * TABLE_OUT: C that #includes the same .cl files as C11 and, for every
 *   `KERNEL void name(args)`, a trampoline that unpacks a generic argument
 *   array, plus the table AMSPH_OMP_TABLE of {name, argument count,
 *   trampoline} for the OpenMP backend. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_INCLUDED 64
#define MAX_ARGS 32

static char included[MAX_INCLUDED][256];
static int n_included;

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "embed_kernels: cannot open %s\n", path);
        exit(1);
    }
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = malloc((size_t)size + 1);
    if (!text || fread(text, 1, (size_t)size, f) != (size_t)size) {
        fprintf(stderr, "embed_kernels: cannot read %s\n", path);
        exit(1);
    }
    text[size] = '\0';
    fclose(f);
    return text;
}

static void emit_string_line(FILE *out, const char *line, size_t len)
{
    fputs("    \"", out);
    for (size_t i = 0; i < len; ++i) {
        const char c = line[i];
        if (c == '\\' || c == '"')
            fputc('\\', out);
        fputc(c, out);
    }
    fputs("\\n\"\n", out);
}

/* Writes file `name` from dir, expanding #include "x" once per file. */
static void emit_flattened(FILE *out, const char *dir, const char *name)
{
    for (int k = 0; k < n_included; ++k)
        if (strcmp(included[k], name) == 0)
            return;
    if (n_included == MAX_INCLUDED || strlen(name) >= sizeof included[0]) {
        fprintf(stderr, "embed_kernels: too many includes at %s\n", name);
        exit(1);
    }
    strcpy(included[n_included++], name);

    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *text = read_file(path);
    for (char *line = text; *line;) {
        char *eol = strchr(line, '\n');
        const size_t len = eol ? (size_t)(eol - line) : strlen(line);
        char header[256];
        if (sscanf(line, " #include \"%255[^\"]\"", header) == 1)
            emit_flattened(out, dir, header);
        else
            emit_string_line(out, line, len);
        line += len + (eol ? 1 : 0);
    }
    free(text);
}

/* Copies s[0..len) trimmed of surrounding white space into dst. */
static void trim_copy(char *dst, size_t cap, const char *s, size_t len)
{
    while (len && isspace((unsigned char)*s))
        ++s, --len;
    while (len && isspace((unsigned char)s[len - 1]))
        --len;
    if (len >= cap)
        len = cap - 1;
    memcpy(dst, s, len);
    dst[len] = '\0';
}

/* Splits "GLOBAL const real *x" into type "GLOBAL const real *" and name "x". */
static void split_argument(const char *arg, char *type, char *name)
{
    size_t end = strlen(arg);
    size_t start = end;
    while (start > 0 && (isalnum((unsigned char)arg[start - 1]) || arg[start - 1] == '_'))
        --start;
    strcpy(name, arg + start);
    trim_copy(type, 256, arg, start);
}

typedef struct {
    char name[128];
    int nargs;
} kernel_entry;

static void emit_trampoline(FILE *out, const char *name, char args[][256], int nargs)
{
    fprintf(out, "static int run_%s(const amsph_omp_arg *a)\n{\n", name);
    for (int k = 0; k < nargs; ++k) {
        char type[256], arg_name[128];
        split_argument(args[k], type, arg_name);
        if (!strchr(type, '*'))
            fprintf(out, "    if (a[%d].size != sizeof(%s))\n        return %d;\n", k, type, k + 1);
    }
    fprintf(out, "    %s(", name);
    for (int k = 0; k < nargs; ++k) {
        char type[256], arg_name[128];
        split_argument(args[k], type, arg_name);
        if (strchr(type, '*'))
            fprintf(out, "%s(%s)a[%d].pointer", k ? ", " : "", type, k);
        else
            fprintf(out, "%s*(const %s *)a[%d].value", k ? ", " : "", type, k);
    }
    fprintf(out, ");\n    return 0;\n}\n\n");
}

/* Finds every "KERNEL void name(...)" in text, emits its trampoline. */
static int scan_kernels(FILE *out, const char *text, kernel_entry *entries, int n, int cap)
{
    const char *marker = "KERNEL void ";
    for (const char *p = strstr(text, marker); p; p = strstr(p + 1, marker)) {
        if (p != text && p[-1] != '\n')
            continue; /* only declarations that start a line */
        const char *open = strchr(p, '(');
        const char *close = open ? strchr(open, ')') : NULL;
        if (!close || n == cap) {
            fprintf(stderr, "embed_kernels: malformed kernel near %.40s\n", p);
            exit(1);
        }
        kernel_entry *e = &entries[n++];
        trim_copy(e->name, sizeof e->name, p + strlen(marker), (size_t)(open - p) - strlen(marker));
        char args[MAX_ARGS][256];
        int nargs = 0;
        for (const char *s = open + 1; s < close && nargs < MAX_ARGS;) {
            const char *comma = memchr(s, ',', (size_t)(close - s));
            const char *end = comma ? comma : close;
            trim_copy(args[nargs++], sizeof args[0], s, (size_t)(end - s));
            s = end + 1;
        }
        e->nargs = nargs;
        emit_trampoline(out, e->name, args, nargs);
    }
    return n;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: embed_kernels SOURCE_OUT TABLE_OUT KERNEL_DIR file.cl...\n");
        return 1;
    }
    FILE *source = fopen(argv[1], "w");
    FILE *table = fopen(argv[2], "w");
    if (!source || !table) {
        fprintf(stderr, "embed_kernels: cannot write outputs\n");
        return 1;
    }
    const char *dir = argv[3];

    fputs("/* generated by cmake/embed_kernels.c from kernels/: do not edit */\n"
          "const char amsph_opencl_source[] =\n",
          source);
    for (int k = 4; k < argc; ++k)
        emit_flattened(source, dir, argv[k]);
    fputs("    ;\n", source);

    fputs("/* generated by cmake/embed_kernels.c from kernels/: do not edit */\n"
          "#include \"backend_openmp_table.h\"\n",
          table);
    for (int k = 4; k < argc; ++k)
        fprintf(table, "#include \"%s\"\n", argv[k]);
    fputs("\n", table);
    kernel_entry entries[256];
    int n = 0;
    for (int k = 4; k < argc; ++k) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, argv[k]);
        char *text = read_file(path);
        n = scan_kernels(table, text, entries, n, 256);
        free(text);
    }
    fputs("const amsph_omp_kernel AMSPH_OMP_TABLE[] = {\n", table);
    for (int k = 0; k < n; ++k)
        fprintf(table, "    {\"%s\", %d, run_%s},\n", entries[k].name, entries[k].nargs,
                entries[k].name);
    fputs("    {0, 0, 0}};\n", table);
    fclose(source);
    fclose(table);
    return 0;
}
