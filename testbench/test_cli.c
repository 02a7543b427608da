/* SPDX-License-Identifier: MIT */
/*
 * Output files and interruption (src/common/np_outfile.h): what is at the path
 * decides how it is written; nothing is replaced that should not be; write
 * errors and signals are reported, never lost. Cases: `cli.<name>`.
 */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "np_common.h"
#include "np_outfile.h"
#include "np_test.h"

#define CHECK(c) NP_CHECK(c, "errno %d (%s)", errno, strerror(errno))

static char dir[256];

static void cleanup(void);

/* A fresh folder per run, removed at exit. */
static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/np_test_cli.%ld", (long)getpid());
    if (mkdir(dir, 0700) == 0)
        atexit(cleanup);
}

static void path_in(char *out, size_t n, const char *name) { snprintf(out, n, "%s/%s", dir, name); }

static int count_tmp(void)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "ls -a %s | grep -c '\\.tmp' > /dev/null", dir);
    return system(cmd) == 0; /* grep -c exits 0 when it found one */
}

static long file_size(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 ? (long)st.st_size : -1;
}

static void cleanup(void)
{
    if (getpid() != atoi(strrchr(dir, '.') + 1))
        return; /* a forked child */
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "note: could not remove %s\n", dir);
}

/* A regular file is replaced atomically: never half-written, untouched by an aborted run. */
static int case_regular_atomic(void)
{
    char p[512];
    path_in(p, sizeof p, "out.txt");
    FILE *f = fopen(p, "w");
    CHECK(f != NULL);
    fputs("old\n", f);
    fclose(f);

    np_outfile o;
    CHECK(np_outfile_open(&o, p, "w") == 0);
    CHECK(o.atomic == 1);
    fputs("new content\n", o.f);
    CHECK(file_size(p) == 4); /* the old file stays until the commit */
    CHECK(np_outfile_close(&o, 0) == 0);
    CHECK(file_size(p) == 4 && !count_tmp());

    CHECK(np_outfile_open(&o, p, "w") == 0);
    fputs("new content\n", o.f);
    CHECK(np_outfile_close(&o, 1) == 0);
    CHECK(file_size(p) == 12 && !count_tmp());

    /* A file in a folder that does not exist: the message says so. */
    char q[512];
    path_in(q, sizeof q, "nosuch/out.txt");
    CHECK(np_outfile_open(&o, q, "w") == -1);
    CHECK(strstr(o.err, "nosuch/out.txt") && strstr(o.err, "folder does not exist"));
    return 0;
}

/* A FIFO is streamed to and stays a FIFO (a simulator reading a pipe). */
static int case_fifo(void)
{
    char p[512];
    path_in(p, sizeof p, "pipe");
    CHECK(mkfifo(p, 0600) == 0);
    pid_t child = fork();
    CHECK(child >= 0);
    if (child == 0) { /* the reader: count bytes, exit with 0 when all 100000 came */
        FILE *r = fopen(p, "r");
        long n = 0;
        while (r && fgetc(r) != EOF)
            n++;
        _exit(n == 100000 ? 0 : 1);
    }
    np_outfile o;
    CHECK(np_outfile_open(&o, p, "w") == 0);
    CHECK(o.atomic == 0);
    for (int i = 0; i < 100000; i++)
        fputc('x', o.f);
    CHECK(np_outfile_close(&o, 1) == 0);
    int st = 0;
    CHECK(waitpid(child, &st, 0) == child && WIFEXITED(st) && WEXITSTATUS(st) == 0);
    struct stat sb;
    CHECK(lstat(p, &sb) == 0 && S_ISFIFO(sb.st_mode));
    CHECK(!count_tmp());
    return 0;
}

/* Character devices are written directly; /dev/full's error is reported. */
static int case_chardev(void)
{
    np_outfile o;
    CHECK(np_outfile_open(&o, "/dev/null", "w") == 0);
    CHECK(o.atomic == 0);
    fputs("discarded\n", o.f);
    CHECK(np_outfile_close(&o, 1) == 0);
    struct stat sb;
    CHECK(stat("/dev/null", &sb) == 0 && S_ISCHR(sb.st_mode));

    if (access("/dev/full", W_OK) == 0) {
        CHECK(np_outfile_open(&o, "/dev/full", "w") == 0);
        for (int i = 0; i < 100000; i++)
            fputs("0123456789", o.f);
        CHECK(np_outfile_close(&o, 1) == -1);
        CHECK(strstr(o.err, "/dev/full") && strstr(o.err, "write error"));
        CHECK(stat("/dev/full", &sb) == 0 && S_ISCHR(sb.st_mode));
    } else {
        printf("note: no writable /dev/full here; its case is skipped\n");
    }
    return 0;
}

/* A symbolic link is written through: the target changes, the link stays a link. */
static int case_symlink(void)
{
    char target[512], link[512], dangling[512], newtarget[512];
    path_in(target, sizeof target, "target.txt");
    path_in(link, sizeof link, "link.txt");
    path_in(dangling, sizeof dangling, "dangling.txt");
    path_in(newtarget, sizeof newtarget, "created.txt");
    FILE *f = fopen(target, "w");
    CHECK(f != NULL);
    fputs("old\n", f);
    fclose(f);
    CHECK(symlink("target.txt", link) == 0); /* relative: resolved from the link's folder */
    CHECK(symlink("created.txt", dangling) == 0);

    np_outfile o;
    CHECK(np_outfile_open(&o, link, "w") == 0);
    fputs("through the link\n", o.f);
    CHECK(np_outfile_close(&o, 1) == 0);
    struct stat sb;
    CHECK(lstat(link, &sb) == 0 && S_ISLNK(sb.st_mode));
    CHECK(file_size(target) == 17);

    CHECK(np_outfile_open(&o, dangling, "w") == 0);
    fputs("new\n", o.f);
    CHECK(np_outfile_close(&o, 1) == 0);
    CHECK(lstat(dangling, &sb) == 0 && S_ISLNK(sb.st_mode));
    CHECK(file_size(newtarget) == 4);

    char loop[512];
    path_in(loop, sizeof loop, "loop");
    CHECK(symlink("loop", loop) == 0);
    CHECK(np_outfile_open(&o, loop, "w") == -1 && strstr(o.err, "too many levels"));
    return 0;
}

/* A directory or a socket is refused with the path named; nothing is created. */
static int case_refuse(void)
{
    np_outfile o;
    CHECK(np_outfile_open(&o, dir, "w") == -1);
    CHECK(strstr(o.err, dir) && strstr(o.err, "is a directory"));

    char p[512];
    path_in(p, sizeof p, "sock");
    int s = socket(AF_UNIX, SOCK_STREAM, 0);
    CHECK(s >= 0);
    struct sockaddr_un a;
    memset(&a, 0, sizeof a);
    a.sun_family = AF_UNIX;
    snprintf(a.sun_path, sizeof a.sun_path, "%.100s", p);
    CHECK(bind(s, (struct sockaddr *)&a, sizeof a) == 0);
    CHECK(np_outfile_open(&o, p, "w") == -1 && strstr(o.err, "is a socket"));
    close(s);
    struct stat sb;
    CHECK(lstat(p, &sb) == 0 && S_ISSOCK(sb.st_mode));
    CHECK(!count_tmp());
    return 0;
}

/*
 * A signal during a write removes the temporary file, leaves the old output
 * in place, prints the note and exits with 128 + the signal.
 */
static int interrupted_by(int sig, int want_status)
{
    char p[512], errpath[512];
    path_in(p, sizeof p, "interrupted.txt");
    path_in(errpath, sizeof errpath, "stderr.txt");
    FILE *f = fopen(p, "w");
    CHECK(f != NULL);
    fputs("kept\n", f);
    fclose(f);
    pid_t child = fork();
    CHECK(child >= 0);
    if (child == 0) {
        int fd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0600);
        dup2(fd, 2);
        np_interrupt_install();
        np_interrupt_note("journal j.jnl keeps 3 blocks; run again with --resume");
        np_outfile o;
        if (np_outfile_open(&o, p, "w") != 0)
            _exit(3);
        for (int i = 0; i < 100000; i++)
            fputs("partial output\n", o.f);
        fflush(o.f);
        raise(sig);
        _exit(4); /* not reached */
    }
    int st = 0;
    CHECK(waitpid(child, &st, 0) == child);
    CHECK(WIFEXITED(st) && WEXITSTATUS(st) == want_status);
    CHECK(file_size(p) == 5); /* the old file, whole */
    CHECK(!count_tmp());
    char msg[1024] = "";
    f = fopen(errpath, "r");
    CHECK(f != NULL);
    size_t n = fread(msg, 1, sizeof msg - 1, f);
    msg[n] = '\0';
    fclose(f);
    printf("stderr of the interrupted child: %s", msg);
    CHECK(strstr(msg, "interrupted") && strstr(msg, "removed 1 unfinished output file"));
    CHECK(strstr(msg, "run again with --resume"));
    unlink(errpath);
    return 0;
}

/*
 * A signal while the note is being rewritten prints a whole note (the previous or the new one), never
 * none and never a torn one: the child rewrites it in a loop, as `stream` does after every result,
 * and is interrupted at 100 points in that loop.
 */
static int case_interrupt_note_race(void)
{
    char errpath[512];
    path_in(errpath, sizeof errpath, "stderr_race.txt");
    static const char *notes[2] = {
        "note A: journal a.jnl keeps 1 of 2 vectors; run again with --resume (not --force) to send the other 1 [A-end]",
        "note B: journal b.jnl keeps 2 of 3 vectors verified (0 errors); run again with --resume to send the rest [B-end]",
    };
    int whole = 0;
    for (int trial = 0; trial < 100; trial++) {
        int ready[2];
        CHECK(pipe(ready) == 0);
        pid_t child = fork();
        CHECK(child >= 0);
        if (child == 0) {
            close(ready[0]);
            int fd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0600);
            dup2(fd, 2);
            np_interrupt_install();
            np_interrupt_note(notes[0]);
            if (write(ready[1], "r", 1) != 1) /* ready: the parent's signal finds a note already set */
                _exit(3);
            for (unsigned i = 0;; i++)
                np_interrupt_note(notes[(i & 1u) ^ 1u]);
        }
        close(ready[1]);
        char c = 0;
        CHECK(read(ready[0], &c, 1) == 1 && c == 'r');
        close(ready[0]);
        /* 50 to 549 microseconds into the loop: thousands of rewrites, a different point each trial. */
        struct timespec ts = { 0, (long)(50 + (trial * 37) % 500) * 1000L };
        nanosleep(&ts, NULL);
        kill(child, SIGINT);
        int st = 0;
        CHECK(waitpid(child, &st, 0) == child);
        CHECK(WIFEXITED(st) && WEXITSTATUS(st) == 130);
        char msg[1024] = "";
        FILE *f = fopen(errpath, "r");
        CHECK(f != NULL);
        size_t n = fread(msg, 1, sizeof msg - 1, f);
        msg[n] = '\0';
        fclose(f);
        if (!strstr(msg, notes[0]) && !strstr(msg, notes[1])) {
            printf("trial %d: the interrupted child printed no whole note: %s", trial, msg);
            return 1;
        }
        whole++;
    }
    printf("100 interruptions mid-rewrite: %d whole notes\n", whole);
    unlink(errpath);
    return 0;
}

static int case_interrupt_sigint(void) { return interrupted_by(SIGINT, 130); }
static int case_interrupt_sigterm(void) { return interrupted_by(SIGTERM, 143); }

static int with_dir(int (*fn)(void))
{
    make_dir();
    return fn();
}
#define CASE(name, fn) \
    static int name(void) { return with_dir(fn); }
CASE(t_regular, case_regular_atomic)
CASE(t_fifo, case_fifo)
CASE(t_chardev, case_chardev)
CASE(t_symlink, case_symlink)
CASE(t_refuse, case_refuse)
CASE(t_sigint, case_interrupt_sigint)
CASE(t_sigterm, case_interrupt_sigterm)
CASE(t_note_race, case_interrupt_note_race)

static int case_numbers(void)
{
    uint64_t v = 0;
    CHECK(np_parse_u64("010", 0, 100, &v) == 0 && v == 10);
    CHECK(np_parse_u64("0x5", 0, 100, &v) == -1);
    CHECK(np_parse_u64("+3", 0, 100, &v) == -1 && np_parse_u64("-3", 0, 100, &v) == -1);
    CHECK(np_parse_u64("", 0, 100, &v) == -1 && np_parse_u64("3abc", 0, 100, &v) == -1);
    CHECK(np_parse_u64(" 3", 0, 100, &v) == -1 && np_parse_u64("101", 0, 100, &v) == -1);
    CHECK(np_parse_u64("18446744073709551615", 0, UINT64_MAX, &v) == 0 && v == UINT64_MAX);
    CHECK(np_parse_u64("18446744073709551616", 0, UINT64_MAX, &v) == -1);
    CHECK(np_parse_u64_hex("ff80", 4, 0, 0xffff, &v) == 0 && v == 0xff80);
    CHECK(np_parse_u64_hex("0xff", 4, 0, 0xffff, &v) == -1 && np_parse_u64_hex("10000", 4, 0, UINT64_MAX, &v) == -1);
    CHECK(np_parse_u64_or_0x("0xff80", 0, 0xffff, &v) == 0 && v == 0xff80);
    CHECK(np_parse_u64_or_0x("65408", 0, 0xffff, &v) == 0 && v == 0xff80);
    CHECK(np_parse_u64_or_0x("0x", 0, 0xffff, &v) == -1 && np_parse_u64_or_0x("0x1g", 0, 0xffff, &v) == -1);
    return 0;
}

static const np_test_case cases[] = {
    { "numbers", case_numbers },
    { "outfile_regular_atomic", t_regular },
    { "outfile_fifo", t_fifo },
    { "outfile_chardev", t_chardev },
    { "outfile_symlink", t_symlink },
    { "outfile_refuse", t_refuse },
    { "interrupt_sigint", t_sigint },
    { "interrupt_sigterm", t_sigterm },
    { "interrupt_note_race", t_note_race },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
