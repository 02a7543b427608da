/* SPDX-License-Identifier: MIT */
/*
 * pty_board - a board on the master side of a pseudo-terminal, so that
 * `noisepipe stream --tty /dev/pts/N` (src/link/link_tty.c) runs without
 * hardware: the slave is where an FT2232H's /dev/ttyUSB1 would be.
 *
 *   pty_board PATHFILE --emulate           the C board emulator (np_board) serves the master
 *   pty_board PATHFILE PROGRAM [ARG...]    PROGRAM (board_sim) runs with stdin and stdout on
 *                                          the master (its stderr is this program's)
 *
 * It opens the pair, sets the slave raw (nothing echoes before the command sets it up
 * itself), writes the slave's path to PATHFILE (through a rename: a reader sees all of it
 * or nothing) and holds its own descriptor of the slave open, so that the board does not see
 * the end of its stream (EIO on the master) before the command has opened the slave. On
 * SIGTERM or SIGINT it closes that descriptor: once the command's is closed too the board
 * sees EIO, the end of its input; it waits for PROGRAM (10 s, then SIGKILL) and exits with its
 * status (0 with --emulate), after one summary line on stderr.
 */
#define _DEFAULT_SOURCE 1
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "np_link.h"

static volatile sig_atomic_t stop;
static void on_term(int sig) { (void)sig; stop = 1; }

static int write_all(int fd, const uint8_t *p, size_t n)
{
    while (n) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: pty_board PATHFILE (--emulate | PROGRAM [ARG...])\n");
        return 2;
    }
    int emulate = strcmp(argv[2], "--emulate") == 0;
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    if (m < 0 || grantpt(m) != 0 || unlockpt(m) != 0) {
        fprintf(stderr, "pty_board: cannot make a pseudo-terminal: %s\n", strerror(errno));
        return 1;
    }
    const char *name = ptsname(m);
    int s = name ? open(name, O_RDWR | O_NOCTTY) : -1;
    struct termios tio;
    if (s < 0 || tcgetattr(s, &tio) != 0) {
        fprintf(stderr, "pty_board: cannot open the slave %s: %s\n", name ? name : "?", strerror(errno));
        return 1;
    }
    cfmakeraw(&tio);
    tcsetattr(s, TCSANOW, &tio);
    fcntl(m, F_SETFD, FD_CLOEXEC);
    fcntl(s, F_SETFD, FD_CLOEXEC);

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_term;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);

    pid_t pid = -1;
    if (!emulate) {
        pid = fork();
        if (pid < 0) {
            fprintf(stderr, "pty_board: fork: %s\n", strerror(errno));
            return 1;
        }
        if (pid == 0) {
            signal(SIGTERM, SIG_DFL);
            signal(SIGINT, SIG_DFL);
            if (dup2(m, 0) >= 0 && dup2(m, 1) >= 0)
                execvp(argv[2], argv + 2);
            fprintf(stderr, "pty_board: cannot run '%s': %s\n", argv[2], strerror(errno));
            _exit(127);
        }
    }
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp", argv[1]);
    FILE *f = fopen(tmp, "w");
    if (!f || fprintf(f, "%s\n", name) < 0 || fclose(f) != 0 || rename(tmp, argv[1]) != 0) {
        fprintf(stderr, "pty_board: cannot write %s: %s\n", argv[1], strerror(errno));
        if (pid > 0)
            kill(pid, SIGKILL);
        return 1;
    }

    np_board *b = NULL;
    if (emulate) {
        np_board_opts bo;
        memset(&bo, 0, sizeof bo);
        if (!(b = np_board_new(&bo))) {
            fprintf(stderr, "pty_board: out of memory\n");
            return 1;
        }
    }
    unsigned long long in_bytes = 0, out_bytes = 0;
    int status = 0, exited = 0;
    uint8_t in[4096], out[4096];
    for (;;) {
        if (stop && s >= 0) {
            close(s); /* the command's end is all that is left: its close is the board's EIO */
            s = -1;
        }
        if (pid > 0 && waitpid(pid, &status, WNOHANG) == pid) {
            exited = 1;
            break;
        }
        if (!emulate) {
            struct timespec ts = { 0, 20000000 };
            nanosleep(&ts, NULL);
            if (s < 0) {
                /* the program has 10 s to see the end of its input and exit */
                pid_t w = 0;
                for (int k = 0; k < 500 && (w = waitpid(pid, &status, WNOHANG)) != pid; k++)
                    nanosleep(&ts, NULL);
                if (w != pid) {
                    kill(pid, SIGKILL);
                    waitpid(pid, &status, 0);
                    fprintf(stderr, "pty_board: %s did not end within 10 s of the end of its input: killed\n",
                            argv[2]);
                    return 1;
                }
                exited = 1;
                break;
            }
            continue;
        }
        struct pollfd pf = { m, POLLIN, 0 };
        int r = poll(&pf, 1, 20);
        if (r <= 0)
            continue;
        ssize_t k = read(m, in, sizeof in);
        if (k < 0 && (errno == EINTR || errno == EAGAIN))
            continue;
        if (k <= 0)
            break; /* EIO: every slave descriptor is closed */
        in_bytes += (unsigned long long)k;
        size_t off = 0;
        while (off < (size_t)k) {
            off += np_board_rx(b, in + off, (size_t)k - off);
            size_t n;
            while ((n = np_board_tx(b, out, sizeof out)) > 0) {
                if (write_all(m, out, n) != 0)
                    break;
                out_bytes += n;
            }
        }
    }
    if (emulate) {
        np_board_free(b);
        fprintf(stderr, "pty_board: the emulator on %s: %llu OUT bytes, %llu IN bytes; end of input\n", name,
                in_bytes, out_bytes);
        return 0;
    }
    (void)exited;
    fprintf(stderr, "pty_board: %s on %s: %s %d\n", argv[2], name,
            WIFEXITED(status) ? "exit status" : "killed by signal",
            WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status));
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}
