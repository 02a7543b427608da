/* SPDX-License-Identifier: MIT */
/*
 * link_fd.c - the host engine over a byte stream of file descriptors: a
 * kernel tty (an FT2232H's channel through ftdi_sio, /dev/ttyUSB1), or the
 * pipes of a board simulator run as a child (np_link_spawn below: `noisepipe
 * stream --sim`). The protocol's byte streams need nothing else
 * (docs/usb-protocol.md section 1: neither side gives packet boundaries a
 * meaning).
 *
 * Both descriptors are made non-blocking for the session (their flags are
 * restored after it) and driven by poll(): OUT bytes are written as the
 * descriptor takes them (partial writes resume where they stopped), IN bytes
 * are read as they come and pushed to the host. Time-outs as the other
 * transports: a board silent for `timeout` seconds while the host waits for a
 * frame, or OUT bytes not taken for that long (a board that holds its flow
 * control), are NP_FAULT_TIMEOUT. End of file on rfd, EPIPE or EIO is the board
 * gone: NP_FAULT_NO_DEVICE. SIGPIPE is ignored during the session (so EPIPE
 * is seen as an error, not as a signal that ends the process) and its old
 * action restored after it.
 *
 * A tty must be set up by the caller (link_tty.c's np_link_tty_open does): raw,
 * the baud rate, CRTSCTS, and VMIN at least 1 (cfmakeraw's): with VMIN = VTIME = 0 a non-blocking read() of a tty
 * with no bytes returns 0, which this transport takes for the end of the stream.
 */
#include "np_link.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "np_common.h"

enum { IN_BYTES = 65536 };

/* The board's end of the stream as a fault of the host; what was outstanding is in the message. */
static void gone(np_host *h, const char *what)
{
    char outs[128];
    np_host_outstanding(h, outs, sizeof outs);
    np_host_fault(h, NP_FAULT_NO_DEVICE, "the board disappeared (%s); %s", what, outs);
}

static int set_nonblock(int fd, int *old)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0)
        return -1;
    *old = fl;
    return (fl & O_NONBLOCK) ? 0 : fcntl(fd, F_SETFL, fl | O_NONBLOCK);
}

void np_link_fd_stream(int rfd, int wfd, np_host *h, const np_fd_opts *o)
{
    double timeout = o && o->timeout > 0 ? o->timeout : 2.0;
    size_t chunk = o && o->chunk ? o->chunk : NP_LINK_MAX_FRAME;
    uint8_t *obuf = malloc(NP_LINK_MAX_FRAME), *ibuf = malloc(IN_BYTES);
    int rfl = -1, wfl = -1;
    if (!obuf || !ibuf) {
        free(obuf);
        free(ibuf);
        np_host_fault(h, NP_FAULT_USB, "out of memory");
        return;
    }
    if (set_nonblock(rfd, &rfl) != 0 || set_nonblock(wfd, &wfl) != 0) {
        np_host_fault(h, NP_FAULT_USB, "cannot make the board's descriptors non-blocking: %s", strerror(errno));
        goto out;
    }
    struct sigaction ign, old_pipe;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigemptyset(&ign.sa_mask);
    sigaction(SIGPIPE, &ign, &old_pipe);

    size_t olen = 0, ooff = 0;
    double last = np_now();
    while (!np_host_done(h) && np_host_get_fault(h) == NP_FAULT_NONE) {
        if (ooff == olen) {
            olen = np_host_pull(h, obuf, NP_LINK_MAX_FRAME);
            ooff = 0;
        }
        if (ooff == olen && !np_host_waiting(h)) {
            np_host_fault(h, NP_FAULT_USB, "internal: the session stalled with nothing to wait for");
            break;
        }
        struct pollfd pf[2];
        memset(pf, 0, sizeof pf);
        pf[0].fd = rfd;
        pf[0].events = POLLIN;
        nfds_t nf = 1;
        if (ooff < olen) {
            pf[1].fd = wfd;
            pf[1].events = POLLOUT;
            nf = 2;
        }
        double left = last + timeout - np_now();
        int ms = left <= 0 ? 0 : left > 0.1 ? 100 : (int)(left * 1000.0) + 1;
        int r = poll(pf, nf, ms);
        if (r < 0 && errno != EINTR) {
            np_host_fault(h, NP_FAULT_USB, "poll on the board's descriptors: %s", strerror(errno));
            break;
        }
        int progress = 0;
        if (r > 0 && nf == 2 && (pf[1].revents & (POLLOUT | POLLERR | POLLHUP))) {
            size_t m = olen - ooff < chunk ? olen - ooff : chunk;
            ssize_t k = write(wfd, obuf + ooff, m);
            if (k > 0) {
                ooff += (size_t)k;
                progress = 1;
            } else if (k < 0 && (errno == EPIPE || errno == EIO)) {
                gone(h, errno == EPIPE ? "write: the other end of its stream is closed" : "write: I/O error");
                break;
            } else if (k < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
                np_host_fault(h, NP_FAULT_USB, "write to the board: %s", strerror(errno));
                break;
            }
        }
        if (r > 0 && (pf[0].revents & (POLLIN | POLLERR | POLLHUP))) {
            /* Read until the descriptor is empty: what is there is pushed before the next frame is pulled. */
            for (;;) {
                ssize_t k = read(rfd, ibuf, IN_BYTES);
                if (k > 0) {
                    progress = 1;
                    if (np_host_push(h, ibuf, (size_t)k) != 0 || np_host_done(h))
                        break;
                    continue;
                }
                if (k == 0)
                    gone(h, "end of its byte stream");
                else if (errno == EIO)
                    gone(h, "read: I/O error");
                else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
                    np_host_fault(h, NP_FAULT_USB, "read from the board: %s", strerror(errno));
                break;
            }
        }
        double now = np_now();
        if (progress) {
            last = now;
        } else if (now - last > timeout && np_host_get_fault(h) == NP_FAULT_NONE) {
            if (ooff < olen) {
                char outs[128];
                np_host_outstanding(h, outs, sizeof outs);
                np_host_fault(h, NP_FAULT_TIMEOUT,
                              "timeout: the board has taken no OUT bytes for %.3g s (%zu of a %zu-byte frame "
                              "left; flow control held?); %s",
                              timeout, olen - ooff, olen, outs);
            } else if (np_host_waiting(h)) {
                np_host_timeout(h, timeout);
            }
        }
    }
    sigaction(SIGPIPE, &old_pipe, NULL);
out:
    if (rfl >= 0)
        fcntl(rfd, F_SETFL, rfl);
    if (wfl >= 0)
        fcntl(wfd, F_SETFL, wfl);
    free(obuf);
    free(ibuf);
}

/* ------------------------------------------------------------------------- */
/* A board simulator as a child process on two pipes. */

static void close_fd(int *fd)
{
    if (*fd >= 0)
        close(*fd);
    *fd = -1;
}

/* pipe() with both ends close-on-exec (pipe2 is not POSIX 2008). */
static int pipe_cloexec(int fd[2])
{
    if (pipe(fd) != 0)
        return -1;
    if (fcntl(fd[0], F_SETFD, FD_CLOEXEC) != 0 || fcntl(fd[1], F_SETFD, FD_CLOEXEC) != 0) {
        close_fd(&fd[0]);
        close_fd(&fd[1]);
        return -1;
    }
    return 0;
}

int np_link_spawn(np_link_child *c, char *const argv[], char *err, size_t errlen)
{
    c->pid = -1;
    c->rfd = c->wfd = -1;
    c->status = 0;
    c->reaped = 0;
    int to_child[2] = { -1, -1 }, from_child[2] = { -1, -1 }, report[2] = { -1, -1 };
    /* O_CLOEXEC: no other child of this process inherits an end, so EOF reaches the simulator. */
    if (pipe_cloexec(to_child) != 0 || pipe_cloexec(from_child) != 0 || pipe_cloexec(report) != 0) {
        snprintf(err, errlen, "cannot make the pipes to '%s': %s", argv[0], strerror(errno));
        goto fail;
    }
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, errlen, "cannot start '%s': fork: %s", argv[0], strerror(errno));
        goto fail;
    }
    if (pid == 0) {
        /* The child: stdin from the host, stdout to the host, stderr shared; no shell. */
        if (dup2(to_child[0], 0) >= 0 && dup2(from_child[1], 1) >= 0)
            execvp(argv[0], argv);
        int e = errno;
        ssize_t w = write(report[1], &e, sizeof e);
        (void)w;
        _exit(127);
    }
    close_fd(&to_child[0]);
    close_fd(&from_child[1]);
    close_fd(&report[1]);
    /* The report pipe closes at exec (CLOEXEC) with nothing in it, or carries exec's errno. */
    int e = 0;
    ssize_t k;
    while ((k = read(report[0], &e, sizeof e)) < 0 && errno == EINTR)
        ;
    close_fd(&report[0]);
    if (k == (ssize_t)sizeof e) {
        waitpid(pid, NULL, 0);
        snprintf(err, errlen, "cannot run '%s': %s", argv[0], strerror(e));
        goto fail;
    }
    c->pid = pid;
    c->wfd = to_child[1];
    c->rfd = from_child[0];
    return 0;
fail:
    close_fd(&to_child[0]);
    close_fd(&to_child[1]);
    close_fd(&from_child[0]);
    close_fd(&from_child[1]);
    close_fd(&report[0]);
    close_fd(&report[1]);
    return -1;
}

int np_link_child_exited(np_link_child *c)
{
    if (c->reaped)
        return 1;
    if (c->pid <= 0)
        return 0;
    pid_t r = waitpid(c->pid, &c->status, WNOHANG);
    if (r == c->pid)
        c->reaped = 1;
    return c->reaped;
}

void np_link_child_status(const np_link_child *c, char *buf, size_t len)
{
    if (!c->reaped)
        snprintf(buf, len, "still running");
    else if (WIFEXITED(c->status))
        snprintf(buf, len, "exit status %d", WEXITSTATUS(c->status));
    else if (WIFSIGNALED(c->status))
        snprintf(buf, len, "killed by signal %d (%s)", WTERMSIG(c->status), strsignal(WTERMSIG(c->status)));
    else
        snprintf(buf, len, "status 0x%x", (unsigned)c->status);
}

int np_link_child_close(np_link_child *c, double grace)
{
    /* EOF on its stdin is the end of the session for a simulator; then it has grace seconds. */
    close_fd(&c->wfd);
    close_fd(&c->rfd);
    if (c->pid <= 0 || c->reaped)
        return c->reaped ? 0 : -1;
    double t0 = np_now();
    int sig = 0;
    while (!np_link_child_exited(c)) {
        double t = np_now() - t0;
        if (sig == 0 && t > grace) {
            kill(c->pid, SIGTERM);
            sig = SIGTERM;
        } else if (sig == SIGTERM && t > grace + 1.0) {
            kill(c->pid, SIGKILL);
            sig = SIGKILL;
        }
        struct timespec ts = { 0, 2000000 };
        nanosleep(&ts, NULL);
    }
    return sig ? 1 : 0;
}
