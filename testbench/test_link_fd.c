/* SPDX-License-Identifier: MIT */
/*
 * test_link_fd.c - the file-descriptor transport (src/link/link_fd.c) and the
 * simulator child on pipes, without a simulator: the board emulator in a
 * thread at the far end of two pipes, moving bytes in odd-sized pieces.
 *
 *   fd_session    a whole session through the pipes, the host writing 3 bytes
 *                 a write(), the board reading 7 and writing 5 at a time
 *   fd_eof        the board closes its IN end part way: NP_FAULT_NO_DEVICE,
 *                 what was verified stays journaled
 *   fd_epipe      the board closes its OUT end at once: EPIPE, NO_DEVICE
 *   fd_timeout    the board reads and never answers: NP_FAULT_TIMEOUT
 *   spawn_missing a program that does not exist: exec's reason
 *   spawn_cat     `cat` as the "board": it echoes the host's frames, which are
 *                 no answer (a time-out); it ends by itself at end of input
 *   spawn_stubborn a child that ignores end of input is stopped (SIGTERM)
 */
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "np_common.h"
#include "np_link.h"
#include "np_test.h"

typedef enum { B_NORMAL, B_CLOSE_IN_AFTER, B_CLOSE_OUT, B_MUTE } board_mode;

typedef struct far_end {
    int rfd, wfd; /* the board's ends: OUT bytes in, IN bytes out */
    board_mode mode;
    size_t close_after; /* B_CLOSE_IN_AFTER: IN bytes written first */
    size_t in_written;
    np_board *b;
} far_end;

static int write_all(int fd, const uint8_t *p, size_t n)
{
    while (n) {
        ssize_t k = write(fd, p, n);
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* The board: read OUT bytes 7 at a time, answer 5 bytes a write(), until end of input. */
static void *board_thread(void *arg)
{
    far_end *e = arg;
    if (e->mode == B_CLOSE_OUT) {
        close(e->rfd);
        e->rfd = -1;
        return NULL;
    }
    uint8_t in[7], out[5];
    for (;;) {
        ssize_t k = read(e->rfd, in, sizeof in);
        if (k <= 0)
            break;
        if (e->mode == B_MUTE)
            continue;
        size_t off = 0;
        while (off < (size_t)k) {
            off += np_board_rx(e->b, in + off, (size_t)k - off);
            size_t m;
            while (e->wfd >= 0 && (m = np_board_tx(e->b, out, sizeof out)) > 0) {
                if (e->mode == B_CLOSE_IN_AFTER && e->in_written + m > e->close_after) {
                    close(e->wfd);
                    e->wfd = -1;
                    break;
                }
                if (write_all(e->wfd, out, m) != 0)
                    break;
                e->in_written += m;
            }
            if (e->wfd < 0)
                off = (size_t)k; /* its IN end is closed: what it gets is dropped */
        }
    }
    return NULL;
}

typedef struct run {
    np_link_job job;
    np_journal jn;
    np_host *h;
    far_end e;
    pthread_t th;
    int joined;
    int host_r, host_w;
} run;

static int run_start(run *r, uint64_t n, board_mode mode)
{
    memset(r, 0, sizeof *r);
    const np_unit *u = np_unit_find("classic3");
    np_unit_cfg cfg;
    char err[256];
    if (!u || np_unit_configure(u, &cfg, NULL, err, sizeof err) != 0 ||
        np_link_job_random(&r->job, u, &cfg, n, 7) != 0 ||
        np_journal_open(&r->jn, NULL, &r->job, 0, err, sizeof err) != 0)
        return -1;
    np_host_opts ho;
    memset(&ho, 0, sizeof ho);
    ho.nonce = 0x1234;
    r->h = np_host_new(&r->job, &r->jn, &ho);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    r->e.b = np_board_new(&bo);
    int to_board[2], to_host[2];
    if (!r->h || !r->e.b || pipe(to_board) != 0 || pipe(to_host) != 0)
        return -1;
    r->e.rfd = to_board[0];
    r->e.wfd = to_host[1];
    r->e.mode = mode;
    r->host_w = to_board[1];
    r->host_r = to_host[0];
    return pthread_create(&r->th, NULL, board_thread, &r->e) == 0 ? 0 : -1;
}

static void run_end(run *r)
{
    close(r->host_w); /* end of input: the board thread ends */
    if (!r->joined)
        pthread_join(r->th, NULL);
    close(r->host_r);
    if (r->e.rfd >= 0)
        close(r->e.rfd);
    if (r->e.wfd >= 0)
        close(r->e.wfd);
    np_board_free(r->e.b);
    np_host_free(r->h);
    np_journal_close(&r->jn);
    np_link_job_free(&r->job);
}

static int test_fd_session(void)
{
    static run r;
    NP_CHECK(run_start(&r, 3000, B_NORMAL) == 0, "set up");
    np_fd_opts o = { 2.0, 3 };
    double t0 = np_now();
    np_link_fd_stream(r.host_r, r.host_w, r.h, &o);
    const np_host_stats *s = np_host_get_stats(r.h);
    NP_CHECK(np_host_done(r.h) && np_host_get_fault(r.h) == NP_FAULT_NONE, "session done: %s",
             np_host_fault_msg(r.h));
    NP_CHECK(r.jn.n_checked == 3000 && r.jn.n_errors == 0 && s->verified == 3000, "3000 verified, got %llu",
             (unsigned long long)r.jn.n_checked);
    NP_CHECK(s->have_bye && s->bye.records == 3000, "the board counted 3000 records");
    printf("fd_session: %llu vectors verified through pipes, %llu OUT bytes in 3-byte writes, %llu IN bytes "
           "in 5-byte writes, %.3f s\n",
           (unsigned long long)s->verified, (unsigned long long)s->bytes_out, (unsigned long long)s->bytes_in,
           np_now() - t0);
    run_end(&r);
    return 0;
}

static int test_fd_eof(void)
{
    static run r;
    NP_CHECK(run_start(&r, 20000, B_CLOSE_IN_AFTER) == 0, "set up");
    r.e.close_after = 20000; /* INFO, CONFIG_ACK, a few RESULTs of 16 KiB frames' 8 KiB */
    np_fd_opts o = { 2.0, 0 };
    np_link_fd_stream(r.host_r, r.host_w, r.h, &o);
    NP_CHECK(np_host_get_fault(r.h) == NP_FAULT_NO_DEVICE, "fault %s: %s",
             np_link_fault_name(np_host_get_fault(r.h)), np_host_fault_msg(r.h));
    NP_CHECK(strstr(np_host_fault_msg(r.h), "end of its byte stream") != NULL, "message: %s",
             np_host_fault_msg(r.h));
    NP_CHECK(r.jn.n_checked > 0 && r.jn.n_checked < 20000 && r.jn.n_errors == 0, "part verified: %llu",
             (unsigned long long)r.jn.n_checked);
    printf("fd_eof: %s; %llu of 20000 verified before\n", np_host_fault_msg(r.h),
           (unsigned long long)r.jn.n_checked);
    run_end(&r);
    return 0;
}

static int test_fd_epipe(void)
{
    static run r;
    NP_CHECK(run_start(&r, 100, B_CLOSE_OUT) == 0, "set up");
    pthread_join(r.th, NULL); /* the OUT end is closed before the host writes */
    r.joined = 1;
    np_fd_opts o = { 2.0, 0 };
    struct sigaction before, after;
    sigaction(SIGPIPE, NULL, &before);
    np_link_fd_stream(r.host_r, r.host_w, r.h, &o);
    NP_CHECK(np_host_get_fault(r.h) == NP_FAULT_NO_DEVICE, "fault %s: %s",
             np_link_fault_name(np_host_get_fault(r.h)), np_host_fault_msg(r.h));
    NP_CHECK(strstr(np_host_fault_msg(r.h), "write") != NULL, "message: %s", np_host_fault_msg(r.h));
    /* SIGPIPE's action is restored: what it was before the session */
    sigaction(SIGPIPE, NULL, &after);
    NP_CHECK(after.sa_handler == before.sa_handler, "SIGPIPE restored");
    printf("fd_epipe: %s\n", np_host_fault_msg(r.h));
    run_end(&r);
    return 0;
}

static int test_fd_timeout(void)
{
    static run r;
    NP_CHECK(run_start(&r, 100, B_MUTE) == 0, "set up");
    np_fd_opts o = { 0.2, 0 };
    double t0 = np_now();
    np_link_fd_stream(r.host_r, r.host_w, r.h, &o);
    double t = np_now() - t0;
    NP_CHECK(np_host_get_fault(r.h) == NP_FAULT_TIMEOUT, "fault %s: %s",
             np_link_fault_name(np_host_get_fault(r.h)), np_host_fault_msg(r.h));
    NP_CHECK(t >= 0.2 && t < 1.5, "after the time-out: %.3f s", t);
    printf("fd_timeout: %s (%.3f s)\n", np_host_fault_msg(r.h), t);
    run_end(&r);
    return 0;
}

static int test_spawn_missing(void)
{
    np_link_child c;
    char err[256] = "";
    char *argv[] = { (char *)"/nonexistent/board_sim", NULL };
    NP_CHECK(np_link_spawn(&c, argv, err, sizeof err) == -1, "refused");
    NP_CHECK(strstr(err, "cannot run '/nonexistent/board_sim': No such file or directory") != NULL, "err: %s",
             err);
    printf("spawn_missing: %s\n", err);
    return 0;
}

static int test_spawn_cat(void)
{
    static run r;
    NP_CHECK(run_start(&r, 100, B_MUTE) == 0, "set up");
    np_link_child c;
    char err[256] = "", st[128];
    char *argv[] = { (char *)"cat", NULL };
    NP_CHECK(np_link_spawn(&c, argv, err, sizeof err) == 0, "cat runs: %s", err);
    np_fd_opts o = { 0.2, 0 };
    np_link_fd_stream(c.rfd, c.wfd, r.h, &o);
    NP_CHECK(np_host_get_fault(r.h) == NP_FAULT_TIMEOUT, "its echo is no answer: %s", np_host_fault_msg(r.h));
    NP_CHECK(np_link_child_close(&c, 2.0) == 0, "cat ends at end of input");
    np_link_child_status(&c, st, sizeof st);
    NP_CHECK(strcmp(st, "exit status 0") == 0, "status: %s", st);
    printf("spawn_cat: %s; cat: %s\n", np_host_fault_msg(r.h), st);
    run_end(&r);
    return 0;
}

static int test_spawn_stubborn(void)
{
    np_link_child c;
    char err[256] = "", st[128];
    char *argv[] = { (char *)"sleep", (char *)"30", NULL };
    NP_CHECK(np_link_spawn(&c, argv, err, sizeof err) == 0, "sleep runs: %s", err);
    double t0 = np_now();
    NP_CHECK(np_link_child_close(&c, 0.1) == 1, "it had to be signalled");
    double t = np_now() - t0;
    np_link_child_status(&c, st, sizeof st);
    NP_CHECK(strncmp(st, "killed by signal 15", 19) == 0, "status: %s", st);
    NP_CHECK(t >= 0.1 && t < 1.0, "stopped after the grace time: %.3f s", t);
    printf("spawn_stubborn: %s after %.3f s\n", st, t);
    return 0;
}

static const np_test_case cases[] = {
    { "fd_session", test_fd_session },       { "fd_eof", test_fd_eof },
    { "fd_epipe", test_fd_epipe },           { "fd_timeout", test_fd_timeout },
    { "spawn_missing", test_spawn_missing }, { "spawn_cat", test_spawn_cat },
    { "spawn_stubborn", test_spawn_stubborn }, { NULL, NULL },
};
NP_TEST_MAIN(cases)
