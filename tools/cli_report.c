/* cli_report.c - what the CLI says: errors in one format ("trigeo: FILE:LINE: message"), the
 * library's diagnostics in it, usage errors pointing at the help, and the work summary's last lines.
 * Based on: the CLI contract of the project's DESIGN.md (exit codes, error format). */
#include "cli.h"

#include <stdarg.h>

void cli_error(const char* file, unsigned long long line, const char* fmt, ...)
{
    va_list ap;
    fputs("trigeo: ", stderr);
    if (file && *file) {
        if (line)
            fprintf(stderr, "%s:%llu: ", file, line);
        else
            fprintf(stderr, "%s: ", file);
    }
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void cli_error_diag(const tg_diag* d, tg_status st)
{
    if (d->message[0]) {
        if (!d->line && d->byte_offset)
            cli_error(d->file, 0, "byte %llu: %s", (unsigned long long)d->byte_offset, d->message);
        else
            cli_error(d->file, d->line, "%s", d->message);
    } else {
        cli_error(d->file, d->line, "%s", tg_status_string(st));
    }
}

int cli_usage(const char* cmd, const char* fmt, ...)
{
    va_list ap;
    fputs("trigeo: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see 'trigeo help %s')\n", cmd ? cmd : "");
    return CLI_USAGE;
}

void cli_print_work(const tg_field_stats* st, double secs)
{
    printf("windows            %llu created, %llu propagated\n", (unsigned long long)st->windows_created,
           (unsigned long long)st->windows_propagated);
    printf("seconds            %.3f\n", secs);
}
