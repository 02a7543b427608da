/* SPDX-License-Identifier: MIT */
/*
 * link_tty.c - a kernel tty as the board's byte stream (`noisepipe stream
 * --tty /dev/ttyUSB1`): the FT2232H's UART channel through the ftdi_sio
 * driver, or any tty that carries the protocol's bytes (a pseudo-terminal in
 * the tests). link_fd.c runs the session on the descriptor; this file opens
 * it and sets it up the way that transport needs (link_fd.c's header):
 *
 *   open O_RDWR | O_NOCTTY | O_NONBLOCK (not the process's controlling tty;
 *        no wait for carrier), then an exclusive lock (TIOCEXCL where there
 *        is one: a second stream on the same board is refused by the kernel);
 *   cfmakeraw: no echo, no line editing, no CR/NL translation, 8 bits, no
 *        parity (8N1 with CSTOPB clear), VMIN 1 / VTIME 0;
 *   CLOCAL | CREAD: no modem control lines needed, the receiver on;
 *   CRTSCTS: the gateware drives the FT2232H's CTS# from its rts_n (docs/
 *        board.md), so the chip must stop sending while it is high;
 *   the baud rate: one of termios' Bnnn rates (3,000,000 the gateware's);
 *   tcflush(TCIOFLUSH): what an earlier session left in either buffer goes.
 *
 * The settings are read back and checked (a driver that cannot set the rate
 * says so), and the old ones restored at close.
 */
#define _DEFAULT_SOURCE 1 /* cfmakeraw, CRTSCTS and the rates above 38400 (not POSIX) */
#include "np_link.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

static const struct {
    unsigned baud;
    speed_t code;
} rates[] = {
    { 9600, B9600 },       { 19200, B19200 },     { 38400, B38400 },     { 57600, B57600 },
    { 115200, B115200 },   { 230400, B230400 },   { 460800, B460800 },   { 500000, B500000 },
    { 576000, B576000 },   { 921600, B921600 },   { 1000000, B1000000 }, { 1152000, B1152000 },
    { 1500000, B1500000 }, { 2000000, B2000000 }, { 2500000, B2500000 }, { 3000000, B3000000 },
#ifdef B3500000
    { 3500000, B3500000 },
#endif
#ifdef B4000000
    { 4000000, B4000000 },
#endif
};

int np_link_tty_baud_ok(unsigned baud)
{
    for (size_t k = 0; k < sizeof rates / sizeof rates[0]; k++)
        if (rates[k].baud == baud)
            return 1;
    return 0;
}

void np_link_tty_rates(char *buf, size_t len)
{
    size_t off = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < sizeof rates / sizeof rates[0] && off < len; k++) {
        int n = snprintf(buf + off, len - off, "%s%u", k ? ", " : "", rates[k].baud);
        if (n < 0)
            break;
        off += (size_t)n;
    }
}

int np_link_tty_open(np_tty *t, const char *path, unsigned baud, char *err, size_t errlen)
{
    t->fd = -1;
    t->have_old = 0;
    speed_t code = 0;
    int found = 0;
    for (size_t k = 0; k < sizeof rates / sizeof rates[0]; k++)
        if (rates[k].baud == baud) {
            code = rates[k].code;
            found = 1;
        }
    if (!found) {
        char list[256];
        np_link_tty_rates(list, sizeof list);
        snprintf(err, errlen, "--tty %s: baud %u is not a rate termios can set (%s)", path, baud, list);
        return -1;
    }
    int fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        snprintf(err, errlen, "--tty %s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    if (!isatty(fd)) {
        snprintf(err, errlen, "--tty %s: not a tty (a serial port such as /dev/ttyUSB1 is)", path);
        close(fd);
        return -1;
    }
#ifdef TIOCEXCL
    ioctl(fd, TIOCEXCL); /* best effort: not every tty driver has it */
#endif
    struct termios old, tio, got;
    if (tcgetattr(fd, &old) != 0) {
        snprintf(err, errlen, "--tty %s: cannot read its settings: %s", path, strerror(errno));
        close(fd);
        return -1;
    }
    tio = old;
    cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD | CRTSCTS;
    tio.c_cflag &= (tcflag_t)~CSTOPB;
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    if (cfsetispeed(&tio, code) != 0 || cfsetospeed(&tio, code) != 0 || tcsetattr(fd, TCSANOW, &tio) != 0) {
        snprintf(err, errlen, "--tty %s: cannot set raw mode at %u baud with RTS/CTS: %s", path, baud, strerror(errno));
        close(fd);
        return -1;
    }
    /* tcsetattr succeeds when any one setting took: read them back. */
    if (tcgetattr(fd, &got) != 0 || cfgetospeed(&got) != code || cfgetispeed(&got) != code ||
        (got.c_lflag & (ICANON | ECHO | ISIG)) || (got.c_cflag & CSIZE) != CS8 || (got.c_cflag & PARENB)) {
        snprintf(err, errlen, "--tty %s: the driver did not take raw mode 8N1 at %u baud", path, baud);
        tcsetattr(fd, TCSANOW, &old);
        close(fd);
        return -1;
    }
    t->rtscts = (got.c_cflag & CRTSCTS) != 0;
    tcflush(fd, TCIOFLUSH);
    t->fd = fd;
    t->old = old;
    t->have_old = 1;
    t->baud = baud;
    return 0;
}

void np_link_tty_close(np_tty *t)
{
    if (t->fd < 0)
        return;
    if (t->have_old)
        tcsetattr(t->fd, TCSANOW, &t->old);
    close(t->fd);
    t->fd = -1;
}
