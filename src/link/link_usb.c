/* SPDX-License-Identifier: MIT */
/*
 * link_usb.c - the libusb transport of the USB link (docs/usb-protocol.md,
 * section 1): asynchronous bulk transfers, several in flight each way, one
 * event loop on libusb_handle_events_timeout_completed.
 *
 * OUT: up to in_flight transfers, one frame each, refilled from np_host_pull
 * as they complete; their time-out is the link time-out (a board that NAKs
 * for that long is a fault). IN: in_flight transfers of a multiple of
 * wMaxPacketSize, resubmitted from the completion callback; completions are
 * handed to the host strictly in submission order (a later transfer can
 * complete first when an earlier one is cancelled), and a cancelled or
 * failed transfer's actual_length bytes are still handed over, so nothing
 * the board sent is lost. A watchdog turns silence into a time-out fault.
 * Every libusb error is reported through libusb_error_name.
 */
#include "np_link.h"

#include <libusb.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"

enum { IN_BYTES = 16384, MAX_IN_FLIGHT = 64 };

typedef struct xfer {
    struct libusb_transfer *t;
    uint8_t *buf;
    int busy; /* submitted, callback not yet run */
    int done; /* IN: callback ran, data not yet handed over */
    struct usb_run *run;
} xfer;

typedef struct usb_run {
    np_host *h;
    libusb_context *ctx;
    libusb_device_handle *dh;
    unsigned ep_out, ep_in, maxp, iface;
    unsigned n;        /* transfers per direction */
    size_t in_bytes;
    unsigned timeout_ms;
    xfer out[MAX_IN_FLIGHT], in[MAX_IN_FLIGHT];
    unsigned order[MAX_IN_FLIGHT]; /* IN transfers in submission order */
    unsigned head, count;
    int stopping;
    int stalled_ep;    /* endpoint to clear, or -1 */
    double last;       /* time of the last progress */
    double last_out;   /* time of the last OUT completion */
} usb_run;

/* A transfer status or libusb error code as a fault of the host. */
static void status_fault(usb_run *r, int status, int is_status, unsigned ep, const char *what)
{
    const char *dir = ep & LIBUSB_ENDPOINT_IN ? "IN" : "OUT";
    char outs[128];
    np_host_outstanding(r->h, outs, sizeof outs);
    int no_dev = is_status ? status == LIBUSB_TRANSFER_NO_DEVICE : status == LIBUSB_ERROR_NO_DEVICE;
    int stall = is_status ? status == LIBUSB_TRANSFER_STALL : status == LIBUSB_ERROR_PIPE;
    int tmo = is_status ? status == LIBUSB_TRANSFER_TIMED_OUT : status == LIBUSB_ERROR_TIMEOUT;
    if (no_dev)
        np_host_fault(r->h, NP_FAULT_NO_DEVICE,
                      "the board disappeared (%s on endpoint 0x%02x %s %s); %s",
                      libusb_error_name(status), ep, dir, what, outs);
    else if (stall) {
        r->stalled_ep = (int)ep;
        np_host_fault(r->h, NP_FAULT_STALL,
                      "endpoint 0x%02x (%s) stalled (%s %s): the board halted the pipe; the host clears the halt; %s",
                      ep, dir, libusb_error_name(status), what, outs);
    } else if (tmo)
        np_host_fault(r->h, NP_FAULT_TIMEOUT,
                      "timeout: the board has taken no data for %.1f s on endpoint 0x%02x %s (%s %s); %s",
                      r->timeout_ms / 1000.0, ep, dir, libusb_error_name(status), what, outs);
    else
        np_host_fault(r->h, NP_FAULT_USB, "USB error on endpoint 0x%02x %s: %s %s; %s", ep, dir,
                      libusb_error_name(status), what, outs);
}

static void LIBUSB_CALL out_cb(struct libusb_transfer *t)
{
    xfer *x = t->user_data;
    usb_run *r = x->run;
    x->busy = 0;
    if (t->status == LIBUSB_TRANSFER_COMPLETED) {
        r->last = r->last_out = np_now();
        return;
    }
    if (t->status == LIBUSB_TRANSFER_CANCELLED && r->stopping)
        return;
    char what[64];
    snprintf(what, sizeof what, "after %d of %d bytes", t->actual_length, t->length);
    status_fault(r, (int)t->status, 1, r->ep_out, what);
}

static void LIBUSB_CALL in_cb(struct libusb_transfer *t);

/* IN transfers have no time-out of their own: the watchdog knows whether silence is a fault. */
static int submit_in(usb_run *r, unsigned k)
{
    xfer *x = &r->in[k];
    libusb_fill_bulk_transfer(x->t, r->dh, (unsigned char)r->ep_in, x->buf, (int)r->in_bytes,
                              in_cb, x, 0);
    int rc = libusb_submit_transfer(x->t);
    if (rc < 0) {
        status_fault(r, rc, 0, r->ep_in, "when submitting");
        return -1;
    }
    x->busy = 1;
    x->done = 0;
    r->order[(r->head + r->count) % r->n] = k;
    r->count++;
    return 0;
}

/* Hand completed IN transfers to the host in submission order; resubmit them. */
static void in_drain(usb_run *r)
{
    while (r->count > 0) {
        unsigned k = r->order[r->head];
        xfer *x = &r->in[k];
        if (!x->done)
            break;
        r->head = (r->head + 1u) % r->n;
        r->count--;
        x->done = 0;
        struct libusb_transfer *t = x->t;
        if (t->actual_length > 0) {
            np_host_push(r->h, x->buf, (size_t)t->actual_length);
            r->last = np_now();
        }
        if (t->status == LIBUSB_TRANSFER_COMPLETED) {
            if (!r->stopping && np_host_get_fault(r->h) == NP_FAULT_NONE && !np_host_done(r->h))
                submit_in(r, k);
        } else if (!(t->status == LIBUSB_TRANSFER_CANCELLED && r->stopping)) {
            status_fault(r, (int)t->status, 1, r->ep_in, "while reading results");
        }
    }
}

static void LIBUSB_CALL in_cb(struct libusb_transfer *t)
{
    xfer *x = t->user_data;
    x->busy = 0;
    x->done = 1;
    in_drain(x->run);
}

static int any_busy(const usb_run *r)
{
    for (unsigned k = 0; k < r->n; k++)
        if (r->out[k].busy || r->in[k].busy)
            return 1;
    return 0;
}

static int errf(char *err, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int errf(char *err, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, len, fmt, ap);
    va_end(ap);
    return -1;
}

/* Find the interface's bulk endpoints (or check the ones given). */
static int find_endpoints(usb_run *r, libusb_device *dev, const np_usb_opts *o, char *err, size_t errlen)
{
    struct libusb_config_descriptor *cd = NULL;
    int rc = libusb_get_active_config_descriptor(dev, &cd);
    if (rc < 0)
        return errf(err, errlen, "cannot read the configuration descriptor: %s", libusb_error_name(rc));
    const struct libusb_interface_descriptor *id = NULL;
    for (unsigned i = 0; i < cd->bNumInterfaces && !id; i++)
        for (int a = 0; a < cd->interface[i].num_altsetting; a++)
            if (cd->interface[i].altsetting[a].bInterfaceNumber == r->iface &&
                cd->interface[i].altsetting[a].bAlternateSetting == 0)
                id = &cd->interface[i].altsetting[a];
    int found_out = -1, found_in = -1;
    if (id)
        for (unsigned e = 0; e < id->bNumEndpoints; e++) {
            const struct libusb_endpoint_descriptor *ed = &id->endpoint[e];
            if ((ed->bmAttributes & 3u) != LIBUSB_TRANSFER_TYPE_BULK)
                continue;
            int in = (ed->bEndpointAddress & LIBUSB_ENDPOINT_IN) != 0;
            if (in && (o->ep_in < 0 ? found_in < 0 : ed->bEndpointAddress == o->ep_in))
                found_in = ed->bEndpointAddress;
            if (!in && (o->ep_out < 0 ? found_out < 0 : ed->bEndpointAddress == o->ep_out))
                found_out = ed->bEndpointAddress;
        }
    libusb_free_config_descriptor(cd);
    if (!id)
        return errf(err, errlen, "the device has no interface %u", r->iface);
    if (found_out < 0)
        return o->ep_out < 0 ? errf(err, errlen, "interface %u has no bulk OUT endpoint", r->iface)
                             : errf(err, errlen, "interface %u has no bulk OUT endpoint 0x%02x", r->iface, o->ep_out);
    if (found_in < 0)
        return o->ep_in < 0 ? errf(err, errlen, "interface %u has no bulk IN endpoint", r->iface)
                            : errf(err, errlen, "interface %u has no bulk IN endpoint 0x%02x", r->iface, o->ep_in);
    r->ep_out = (unsigned)found_out;
    r->ep_in = (unsigned)found_in;
    rc = libusb_get_max_packet_size(dev, (unsigned char)r->ep_in);
    if (rc <= 0)
        return errf(err, errlen, "cannot read wMaxPacketSize of endpoint 0x%02x: %s", r->ep_in,
                    libusb_error_name(rc));
    r->maxp = (unsigned)rc;
    return 0;
}

static int open_board(usb_run *r, const np_usb_opts *o, np_usb_info *info, char *err, size_t errlen)
{
    int rc = libusb_init(&r->ctx);
    if (rc < 0) {
        r->ctx = NULL;
        return errf(err, errlen, "libusb_init failed: %s", libusb_error_name(rc));
    }
    libusb_device **list = NULL;
    ssize_t nd = libusb_get_device_list(r->ctx, &list);
    if (nd < 0)
        return errf(err, errlen, "cannot list USB devices: %s", libusb_error_name((int)nd));
    libusb_device *dev = NULL;
    for (ssize_t k = 0; k < nd && !dev; k++) {
        struct libusb_device_descriptor dd;
        if (libusb_get_device_descriptor(list[k], &dd) == 0 && dd.idVendor == o->vid && dd.idProduct == o->pid)
            dev = list[k];
    }
    if (!dev) {
        libusb_free_device_list(list, 1);
        return errf(err, errlen, "no USB device %04x:%04x found (is the board plugged in and powered?)", o->vid, o->pid);
    }
    rc = libusb_open(dev, &r->dh);
    if (rc < 0) {
        r->dh = NULL;
        unsigned bus = libusb_get_bus_number(dev), addr = libusb_get_device_address(dev);
        libusb_free_device_list(list, 1);
        if (rc == LIBUSB_ERROR_ACCESS)
            return errf(err, errlen, "permission denied opening %04x:%04x (bus %03u device %03u): give your user access to /dev/bus/usb/%03u/%03u with a udev rule",
                        o->vid, o->pid, bus, addr, bus, addr);
        return errf(err, errlen, "cannot open %04x:%04x: %s", o->vid, o->pid, libusb_error_name(rc));
    }
    rc = find_endpoints(r, dev, o, err, errlen);
    info->speed = libusb_get_device_speed(dev);
    libusb_free_device_list(list, 1);
    if (rc != 0)
        return -1;
    libusb_set_auto_detach_kernel_driver(r->dh, 1); /* LIBUSB_ERROR_NOT_SUPPORTED is fine */
    rc = libusb_claim_interface(r->dh, (int)r->iface);
    if (rc < 0)
        return errf(err, errlen, "cannot claim interface %u of %04x:%04x: %s%s", r->iface, o->vid, o->pid,
                    libusb_error_name(rc), rc == LIBUSB_ERROR_BUSY ? " (another program or driver has it)" : "");
    /* Reset the data toggles and any halt left by an earlier run (section 1). */
    rc = libusb_clear_halt(r->dh, (unsigned char)r->ep_out);
    if (rc == 0)
        rc = libusb_clear_halt(r->dh, (unsigned char)r->ep_in);
    if (rc < 0) {
        libusb_release_interface(r->dh, (int)r->iface);
        return errf(err, errlen, "cannot clear the endpoints' halt: %s", libusb_error_name(rc));
    }
    return 0;
}

static void close_board(usb_run *r)
{
    for (unsigned k = 0; k < MAX_IN_FLIGHT; k++) {
        /* A transfer libusb still owns (its cancellation never completed) is leaked, not freed. */
        if (r->out[k].t && !r->out[k].busy) {
            libusb_free_transfer(r->out[k].t);
            free(r->out[k].buf);
        }
        if (r->in[k].t && !r->in[k].busy) {
            libusb_free_transfer(r->in[k].t);
            free(r->in[k].buf);
        }
    }
    if (r->dh) {
        libusb_release_interface(r->dh, (int)r->iface);
        libusb_close(r->dh);
    }
    if (r->ctx)
        libusb_exit(r->ctx);
}

struct np_usb_board {
    usb_run r;
};

/* iSerialNumber's string into info->serial ("" when the device has none or it cannot be read). */
static void read_serial(usb_run *r, np_usb_info *info)
{
    struct libusb_device_descriptor dd;
    info->serial[0] = '\0';
    if (libusb_get_device_descriptor(libusb_get_device(r->dh), &dd) != 0)
        return;
    unsigned char s[sizeof info->serial];
    int n = dd.iSerialNumber ? libusb_get_string_descriptor_ascii(r->dh, dd.iSerialNumber, s, (int)sizeof s - 1) : 0;
    if (n <= 0)
        return;
    s[n] = '\0';
    for (int k = 0; k < n; k++)
        info->serial[k] = s[k] > 0x20 && s[k] < 0x7f ? (char)s[k] : '_';
    info->serial[n] = '\0';
}

int np_link_usb_open(np_usb_board **out, const np_usb_opts *o, np_usb_info *info, char *err, size_t errlen)
{
    *out = NULL;
    np_usb_board *ub = calloc(1, sizeof *ub);
    if (!ub)
        return errf(err, errlen, "out of memory");
    usb_run *r = &ub->r;
    memset(info, 0, sizeof *info);
    r->iface = o->interface < 0 ? 0u : (unsigned)o->interface;
    r->n = o->in_flight ? o->in_flight : 8u;
    if (r->n > MAX_IN_FLIGHT)
        r->n = MAX_IN_FLIGHT;
    r->timeout_ms = (unsigned)((o->timeout > 0 ? o->timeout : 2.0) * 1000.0 + 0.5);
    r->stalled_ep = -1;
    if (open_board(r, o, info, err, errlen) != 0) {
        close_board(r);
        free(ub);
        return -1;
    }
    read_serial(r, info);
    info->vid = o->vid;
    info->pid = o->pid;
    /* IN transfers: a multiple of wMaxPacketSize, so the board cannot overflow them. */
    r->in_bytes = ((size_t)IN_BYTES + r->maxp - 1u) / r->maxp * r->maxp;
    for (unsigned k = 0; k < r->n; k++) {
        r->out[k].t = libusb_alloc_transfer(0);
        r->out[k].buf = malloc(NP_LINK_MAX_FRAME);
        r->in[k].t = libusb_alloc_transfer(0);
        r->in[k].buf = malloc(r->in_bytes);
        r->out[k].run = r->in[k].run = r;
        if (!r->out[k].t || !r->out[k].buf || !r->in[k].t || !r->in[k].buf) {
            close_board(r);
            free(ub);
            return errf(err, errlen, "out of memory for transfers");
        }
    }
    info->ep_out = r->ep_out;
    info->ep_in = r->ep_in;
    info->max_packet = r->maxp;
    info->in_flight = r->n;
    info->in_transfer = r->in_bytes;
    *out = ub;
    return 0;
}

void np_link_usb_close(np_usb_board *ub)
{
    if (!ub)
        return;
    close_board(&ub->r);
    free(ub);
}

void np_link_usb_stream(np_usb_board *ub, np_host *h)
{
    usb_run *r = &ub->r;
    r->h = h;
    r->last = r->last_out = np_now();
    for (unsigned k = 0; k < r->n; k++)
        if (submit_in(r, k) != 0)
            break;
    double timeout = r->timeout_ms / 1000.0;
    while (np_host_get_fault(h) == NP_FAULT_NONE && !np_host_done(h)) {
        for (unsigned k = 0; k < r->n; k++) {
            xfer *x = &r->out[k];
            if (x->busy)
                continue;
            size_t len = np_host_pull(h, x->buf, NP_LINK_MAX_FRAME);
            if (!len)
                break;
            libusb_fill_bulk_transfer(x->t, r->dh, (unsigned char)r->ep_out, x->buf, (int)len, out_cb, x,
                                      r->timeout_ms);
            int rc = libusb_submit_transfer(x->t);
            if (rc < 0) {
                status_fault(r, rc, 0, r->ep_out, "when submitting");
                break;
            }
            x->busy = 1;
        }
        if (np_host_get_fault(h) != NP_FAULT_NONE)
            break;
        struct timeval tv = { 0, 50000 };
        int rc = libusb_handle_events_timeout_completed(r->ctx, &tv, NULL);
        if (rc < 0 && rc != LIBUSB_ERROR_INTERRUPTED) {
            np_host_fault(h, rc == LIBUSB_ERROR_NO_DEVICE ? NP_FAULT_NO_DEVICE : NP_FAULT_USB,
                          "libusb event handling failed: %s", libusb_error_name(rc));
            break;
        }
        double now = np_now();
        unsigned out_busy = 0;
        for (unsigned k = 0; k < r->n; k++)
            out_busy += (unsigned)r->out[k].busy;
        if (out_busy && now - r->last_out > timeout) {
            char outs[128];
            np_host_outstanding(h, outs, sizeof outs);
            np_host_fault(h, NP_FAULT_TIMEOUT,
                          "timeout: the board has taken no data for %.1f s: %u OUT transfer%s wait on endpoint 0x%02x (it NAKs); %s",
                          timeout, out_busy, out_busy == 1 ? "" : "s", r->ep_out, outs);
        } else if (np_host_waiting(h) && now - r->last > timeout) {
            np_host_timeout(h, timeout);
        }
    }
    /* Stop: cancel what is in flight, keep what it carried, wait (bounded). */
    r->stopping = 1;
    for (unsigned k = 0; k < r->n; k++) {
        if (r->out[k].busy)
            libusb_cancel_transfer(r->out[k].t);
        if (r->in[k].busy)
            libusb_cancel_transfer(r->in[k].t);
    }
    double deadline = np_now() + 1.0;
    while (any_busy(r) && np_now() < deadline) {
        struct timeval tv = { 0, 10000 };
        if (libusb_handle_events_timeout_completed(r->ctx, &tv, NULL) < 0)
            break;
    }
    if (r->stalled_ep >= 0)
        libusb_clear_halt(r->dh, (unsigned char)r->stalled_ep);
}
