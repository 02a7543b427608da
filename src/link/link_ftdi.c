/* SPDX-License-Identifier: MIT */
/*
 * link_ftdi.c - the host engine through an FTDI FT2232H's UART channel, with
 * libftdi1 (docs/board.md, "The host through the FT2232H"). The FTDI chip
 * does not present the protocol's vendor interface (docs/usb-protocol.md
 * section 1): it has its own, and every IN packet starts with two modem-status
 * bytes, which ftdi_read_data strips. On open: the channel (interface B on the
 * iCE40-HX8K breakout), UART mode (bit mode reset), the baud rate, 8N1,
 * RTS/CTS flow control (the gateware holds the FT2232H's CTS# high while its
 * OUT buffer is nearly full), the latency timer (1 ms: a short RESULT is not
 * held back 16 ms), and both buffers purged so no byte of an earlier session
 * reaches this one.
 *
 * The gateware does not watch the FT2232H's RTS# (the IN direction has no flow
 * control): the host reads between OUT chunks of at most CHUNK bytes, so at
 * most a chunk's time of IN bytes (CHUNK bytes at the same baud rate) waits in
 * the chip's 4 KiB receive buffer, well inside it.
 */
#include "np_link.h"

#include <ftdi.h>
#include <libusb.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"

enum { CHUNK = 512, IN_BYTES = 4096 };

struct np_ftdi_board {
    struct ftdi_context *ctx;
    double timeout;
};

static const char *iface_name(int i) { return i == 0 ? "A" : i == 1 ? "B" : i == 2 ? "C" : "D"; }

int np_link_ftdi_open(np_ftdi_board **out, const np_ftdi_opts *o, np_ftdi_info *info, char *err,
                      size_t errlen)
{
    *out = NULL;
    memset(info, 0, sizeof *info);
    struct ftdi_context *c = ftdi_new();
    if (!c) {
        snprintf(err, errlen, "--ftdi: libftdi could not allocate its context");
        return -1;
    }
    static const enum ftdi_interface ifs[4] = { INTERFACE_A, INTERFACE_B, INTERFACE_C, INTERFACE_D };
    const char *step = "ftdi_set_interface";
    int rc = ftdi_set_interface(c, ifs[o->interface & 3]);
    if (rc == 0) {
        step = "open";
        rc = ftdi_usb_open_desc_index(c, o->vid, o->pid, NULL, o->serial[0] ? o->serial : NULL, 0);
        if (rc < 0) {
            if (rc == -3)
                snprintf(err, errlen,
                         "--ftdi %04x:%04x: no such USB device (is the board plugged in? lsusb lists it as "
                         "'Future Technology Devices International'%s%s)",
                         o->vid, o->pid, o->serial[0] ? ", serial " : "", o->serial);
            else
                snprintf(err, errlen, "--ftdi %04x:%04x interface %s: cannot open it: %s (permissions: a udev rule "
                         "for the device, or the ftdi_sio driver holding the channel)",
                         o->vid, o->pid, iface_name(o->interface), ftdi_get_error_string(c));
            ftdi_free(c);
            return -1;
        }
    }
    if (rc == 0 && (step = "bit mode reset (UART)", rc = ftdi_set_bitmode(c, 0, BITMODE_RESET)) == 0 &&
        (step = "--baud", rc = ftdi_set_baudrate(c, (int)o->baud)) == 0 &&
        (step = "8N1", rc = ftdi_set_line_property(c, BITS_8, STOP_BIT_1, NONE)) == 0 &&
        (step = "RTS/CTS flow control", rc = ftdi_setflowctrl(c, SIO_RTS_CTS_HS)) == 0 &&
        (step = "latency timer", rc = ftdi_set_latency_timer(c, 1)) == 0 &&
        (step = "purge", rc = ftdi_tcioflush(c)) == 0) {
        c->usb_read_timeout = 20;
        c->usb_write_timeout = (int)(o->timeout * 1000.0);
        ftdi_read_data_set_chunksize(c, IN_BYTES);
        struct libusb_device *dev = libusb_get_device(c->usb_dev);
        char serial[sizeof info->serial];
        serial[0] = '\0';
        if (ftdi_usb_get_strings2(c, dev, NULL, 0, NULL, 0, serial, (int)sizeof serial) != 0)
            serial[0] = '\0';
        snprintf(info->serial, sizeof info->serial, "%s", serial);
        info->baud = c->baudrate;
        np_ftdi_board *b = calloc(1, sizeof *b);
        if (!b) {
            snprintf(err, errlen, "out of memory");
            ftdi_usb_close(c);
            ftdi_free(c);
            return -1;
        }
        b->ctx = c;
        b->timeout = o->timeout > 0 ? o->timeout : 2.0;
        *out = b;
        return 0;
    }
    snprintf(err, errlen, "--ftdi %04x:%04x interface %s: %s failed: %s", o->vid, o->pid, iface_name(o->interface),
             step, ftdi_get_error_string(c));
    ftdi_usb_close(c);
    ftdi_free(c);
    return -1;
}

/* A libftdi error (a libusb one underneath) as a fault of the host. */
static void ftdi_fault(np_host *h, struct ftdi_context *c, int rc, const char *what)
{
    char outs[128];
    np_host_outstanding(h, outs, sizeof outs);
    /* libftdi returns the libusb code for a failed transfer: -4 is LIBUSB_ERROR_NO_DEVICE, -7 a time-out */
    if (rc == LIBUSB_ERROR_NO_DEVICE || rc == LIBUSB_ERROR_IO)
        np_host_fault(h, NP_FAULT_NO_DEVICE, "the board disappeared (%s: %s); %s", what, ftdi_get_error_string(c),
                      outs);
    else if (rc == LIBUSB_ERROR_TIMEOUT)
        np_host_fault(h, NP_FAULT_TIMEOUT, "timeout: the FT2232H has taken no data (%s; CTS# held high?); %s",
                      what, outs);
    else
        np_host_fault(h, NP_FAULT_USB, "USB error (%s): %s (%d); %s", what, ftdi_get_error_string(c), rc, outs);
}

void np_link_ftdi_stream(np_ftdi_board *b, np_host *h)
{
    uint8_t *obuf = malloc(NP_LINK_MAX_FRAME), *ibuf = malloc(IN_BYTES);
    if (!obuf || !ibuf) {
        free(obuf);
        free(ibuf);
        np_host_fault(h, NP_FAULT_USB, "out of memory");
        return;
    }
    size_t olen = 0, ooff = 0;
    double last = np_now();
    while (!np_host_done(h) && np_host_get_fault(h) == NP_FAULT_NONE) {
        int progress = 0;
        if (ooff == olen) {
            olen = np_host_pull(h, obuf, NP_LINK_MAX_FRAME);
            ooff = 0;
        }
        if (ooff < olen) {
            size_t m = olen - ooff < CHUNK ? olen - ooff : CHUNK;
            int k = ftdi_write_data(b->ctx, obuf + ooff, (int)m);
            if (k < 0) {
                ftdi_fault(h, b->ctx, k, "write");
                break;
            }
            ooff += (size_t)k;
            progress |= k > 0;
        }
        int k = ftdi_read_data(b->ctx, ibuf, IN_BYTES);
        if (k < 0) {
            ftdi_fault(h, b->ctx, k, "read");
            break;
        }
        if (k > 0) {
            np_host_push(h, ibuf, (size_t)k);
            progress = 1;
        }
        double now = np_now();
        if (progress)
            last = now;
        else if (np_host_waiting(h) && now - last > b->timeout)
            np_host_timeout(h, b->timeout);
    }
    free(obuf);
    free(ibuf);
}

void np_link_ftdi_close(np_ftdi_board *b)
{
    if (!b)
        return;
    ftdi_usb_close(b->ctx);
    ftdi_free(b->ctx);
    free(b);
}
