/* SPDX-License-Identifier: MIT */
/*
 * test_link_usb.c - the real libusb path without a board.
 *
 * A UMockdevTestbed holds a USB device (the descriptors of
 * docs/usb-protocol.md, section 1) whose /dev/bus/usb node answers usbdevfs
 * ioctls from this program: SUBMITURB feeds OUT data to the board emulator
 * (np_board) and fills IN URBs from it; REAPURBNDELAY hands completed URBs
 * back; DISCARDURB cancels. Unmodified `noisepipe stream --device` runs in a
 * child process (umockdev-wrapper preloads the emulation library, which the
 * child inherits) and finds, claims and streams to the device with its
 * ordinary libusb code. USB-level faults are made here (the device
 * disappears: URBs end with -ENODEV and every later ioctl fails with ENODEV;
 * the IN endpoint stalls: URBs end with -EPIPE until CLEAR_HALT; the child
 * is killed), protocol-level ones by the emulator (np_board_fault).
 *
 * Run under umockdev-wrapper: `umockdev-wrapper test_link_usb CASE`;
 * `... test_link_usb bench [N]` prints the figures.
 */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <linux/usbdevice_fs.h>
#include <umockdev.h>

#include "np_child.h"
#include "np_common.h"
#include "np_link.h"
#include "np_rng.h"
#include "np_test.h"

#define DEVNODE "/dev/bus/usb/001/002"

/* docs/usb-protocol.md, section 1: device, configuration, interface, two bulk endpoints. */
static const char device_record[] =
    "P: /devices/pci0000:00/usb1/1-1\n"
    "N: bus/usb/001/002\n"
    "E: SUBSYSTEM=usb\n"
    "E: DRIVER=usb\n"
    "E: BUSNUM=001\n"
    "E: DEVNUM=002\n"
    "E: DEVNAME=" DEVNODE "\n"
    "E: DEVTYPE=usb_device\n"
    "A: bConfigurationValue=1\\n\n"
    "A: busnum=1\\n\n"
    "A: devnum=2\\n\n"
    "A: speed=480\\n\n"
    "H: descriptors=120100020000004009120100000101020301"
    "0902200001010080320904000002ff4e0100"
    "07050102000200"
    "07058102000200\n";

typedef struct urb_rec {
    UMockdevIoctlData *urb, *buf;
} urb_rec;

typedef struct dev {
    UMockdevTestbed *tb;
    UMockdevIoctlBase *handler;
    GMutex lock;
    np_board *board;
    GQueue pend_out, pend_in, done;
    /* USB faults, by records the board has taken (0 = never). */
    uint64_t gone_at, stall_at, kill_at, nak_at;
    int kill_sig; /* the signal kill_at sends; 0: SIGKILL */
    int gone, in_halted, stalled, killed;
    unsigned clear_halts_after_stall;
    volatile pid_t child;
    uint64_t submits, reaps, discards;
    char serial[32]; /* string descriptor 3 (iSerialNumber), "NP-0001" unless a test swaps boards */
} dev;

static struct usbdevfs_urb *urb_of(const urb_rec *r) { return (struct usbdevfs_urb *)r->urb->data; }

static void finish(dev *d, urb_rec *r, int status, int actual)
{
    urb_of(r)->status = status;
    urb_of(r)->actual_length = actual;
    g_queue_push_tail(&d->done, r);
}

static void fail_all(dev *d, GQueue *q, int status)
{
    urb_rec *r;
    while ((r = g_queue_pop_head(q)) != NULL)
        finish(d, r, status, 0);
}

static uint64_t records(const dev *d) { return np_board_get_stats(d->board)->records; }

static void usb_faults(dev *d)
{
    uint64_t n = records(d);
    if (d->kill_at && n >= d->kill_at && !d->killed && d->child > 0) {
        kill(d->child, d->kill_sig ? d->kill_sig : SIGKILL);
        d->killed = 1;
    }
    if (d->gone_at && n >= d->gone_at && !d->gone) {
        d->gone = 1; /* unplugged: what is in flight ends with -ENODEV */
        fail_all(d, &d->pend_out, -ENODEV);
        fail_all(d, &d->pend_in, -ENODEV);
    }
    if (d->stall_at && n >= d->stall_at && !d->stalled) {
        d->stalled = d->in_halted = 1;
        fail_all(d, &d->pend_in, -EPIPE);
    }
}

/* Move bytes between the URBs and the board until nothing moves. */
static void pump(dev *d)
{
    for (int progress = 1; progress && !d->gone;) {
        progress = 0;
        urb_rec *r;
        while (!d->gone && (r = g_queue_peek_head(&d->pend_out)) != NULL) {
            int len = urb_of(r)->buffer_length;
            if (d->nak_at && records(d) >= d->nak_at)
                break; /* the board NAKs every OUT packet from now on */
            if (len > 0 && np_board_rx(d->board, r->buf->data, (size_t)len) == 0)
                break; /* NAK: the board's IN queue is full */
            g_queue_pop_head(&d->pend_out);
            finish(d, r, 0, len);
            progress = 1;
            usb_faults(d);
        }
        while (!d->gone && !d->in_halted && np_board_tx_pending(d->board) > 0 &&
               (r = g_queue_pop_head(&d->pend_in)) != NULL) {
            /* The board ends its burst when its queue runs empty: a short packet completes the URB. */
            size_t m = np_board_tx(d->board, r->buf->data, (size_t)urb_of(r)->buffer_length);
            finish(d, r, 0, (int)m);
            progress = 1;
        }
    }
}

/* A control URB on endpoint 0: GET_DESCRIPTOR(STRING) answered (the serial number); others stall. */
static void control_urb(dev *d, urb_rec *r)
{
    struct usbdevfs_urb *u = urb_of(r);
    const uint8_t *setup = r->buf ? (const uint8_t *)r->buf->data : NULL;
    if (!setup || u->buffer_length < 8 || setup[0] != 0x80 || setup[1] != 6 || setup[3] != 3) {
        finish(d, r, -EPIPE, 0);
        return;
    }
    uint8_t desc[2 + 2 * 64];
    unsigned n = 0;
    const char *text = setup[2] == 1 ? "noisepipe" : setup[2] == 2 ? "board emulator" : d->serial;
    if (setup[2] == 0) { /* the language IDs: US English */
        desc[2] = 0x09;
        desc[3] = 0x04;
        n = 4;
    } else {
        for (n = 2; *text && n + 2 <= sizeof desc; text++, n += 2) {
            desc[n] = (uint8_t)*text;
            desc[n + 1] = 0;
        }
    }
    desc[0] = (uint8_t)n;
    desc[1] = 3;
    unsigned want = (unsigned)setup[6] | (unsigned)setup[7] << 8;
    if (n > want)
        n = want;
    if (n > (unsigned)u->buffer_length - 8u)
        n = (unsigned)u->buffer_length - 8u;
    memcpy((uint8_t *)r->buf->data + 8, desc, n);
    finish(d, r, 0, (int)n);
}

static gboolean remove_rec(GQueue *q, gulong addr, urb_rec **out)
{
    for (GList *l = q->head; l; l = l->next) {
        urb_rec *r = l->data;
        if (r->urb->client_addr == addr) {
            g_queue_delete_link(q, l);
            *out = r;
            return TRUE;
        }
    }
    return FALSE;
}

static void ok(UMockdevIoctlClient *c) { umockdev_ioctl_client_complete(c, 0, 0); }
static void fail(UMockdevIoctlClient *c, int e) { umockdev_ioctl_client_complete(c, -1, e); }

/* umockdev_ioctl_data_resolve reads the client's memory; it fails (NULL) when the client is going away,
   e.g. a SIGINT landing while the client waits in an ioctl. The ioctl then ends with EFAULT and the
   emulator holds nothing of it (before, a NULL buffer reached pump: the usb.interrupt crash, about 1 run
   in 20). */
static UMockdevIoctlData *resolve(UMockdevIoctlData *from, gsize offset, gsize len)
{
    GError *e = NULL;
    UMockdevIoctlData *a = umockdev_ioctl_data_resolve(from, offset, len, &e);
    if (!a) {
        fprintf(stderr, "test_link_usb: the client's memory could not be read (%s): the ioctl fails with EFAULT\n",
                e ? e->message : "no reason given");
        g_clear_error(&e);
    }
    return a;
}

static gboolean on_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *c, gpointer user)
{
    dev *d = user;
    gulong req = umockdev_ioctl_client_get_request(c);
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(c);
    gboolean handled = TRUE;
    g_mutex_lock(&d->lock);
    switch (req) {
    case USBDEVFS_GET_CAPABILITIES: {
        UMockdevIoctlData *a = resolve(arg, 0, sizeof(guint32));
        if (!a) {
            fail(c, EFAULT);
            break;
        }
        *(guint32 *)a->data = USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                              USBDEVFS_CAP_REAP_AFTER_DISCONNECT | USBDEVFS_CAP_ZERO_PACKET;
        ok(c);
        g_object_unref(a);
        break;
    }
    case USBDEVFS_CLAIMINTERFACE:
    case USBDEVFS_RELEASEINTERFACE:
    case USBDEVFS_SETINTERFACE:
    case USBDEVFS_RESET:
    case USBDEVFS_RESETEP:
    case USBDEVFS_DISCONNECT_CLAIM:
        if (d->gone)
            fail(c, ENODEV);
        else
            ok(c);
        break;
    case USBDEVFS_GETDRIVER:
    case USBDEVFS_IOCTL:
        fail(c, d->gone ? ENODEV : ENODATA); /* no kernel driver bound */
        break;
    case USBDEVFS_CLEAR_HALT: {
        UMockdevIoctlData *a = resolve(arg, 0, sizeof(unsigned int));
        if (!a) {
            fail(c, EFAULT);
            break;
        }
        unsigned ep = *(unsigned int *)a->data;
        g_object_unref(a);
        if (d->gone) {
            fail(c, ENODEV);
            break;
        }
        if (ep == 0x81 && d->stalled) {
            d->in_halted = 0;
            d->clear_halts_after_stall++;
        }
        ok(c);
        break;
    }
    case USBDEVFS_SUBMITURB: {
        if (d->gone) {
            fail(c, ENODEV);
            break;
        }
        UMockdevIoctlData *urb = resolve(arg, 0, sizeof(struct usbdevfs_urb));
        if (!urb) {
            fail(c, EFAULT);
            break;
        }
        struct usbdevfs_urb *u = (struct usbdevfs_urb *)urb->data;
        UMockdevIoctlData *buf = NULL;
        if (u->buffer_length > 0 &&
            !(buf = resolve(urb, G_STRUCT_OFFSET(struct usbdevfs_urb, buffer), (gsize)u->buffer_length))) {
            g_object_unref(urb);
            fail(c, EFAULT);
            break;
        }
        urb_rec *r = g_new0(urb_rec, 1);
        r->urb = urb;
        r->buf = buf;
        d->submits++;
        if (u->type == USBDEVFS_URB_TYPE_CONTROL && u->endpoint == 0) {
            control_urb(d, r);
        } else if (u->type != USBDEVFS_URB_TYPE_BULK || (u->endpoint != 0x01 && u->endpoint != 0x81)) {
            fprintf(stderr, "test_link_usb: unexpected URB type %u endpoint 0x%02x\n", u->type, u->endpoint);
            finish(d, r, -EINVAL, 0);
        } else if (u->endpoint & 0x80) {
            if (d->in_halted)
                finish(d, r, -EPIPE, 0);
            else
                g_queue_push_tail(&d->pend_in, r);
        } else {
            g_queue_push_tail(&d->pend_out, r);
        }
        ok(c);
        pump(d);
        break;
    }
    case USBDEVFS_DISCARDURB: {
        gulong addr = *(gulong *)arg->data;
        urb_rec *r = NULL;
        d->discards++;
        if (remove_rec(&d->pend_in, addr, &r) || remove_rec(&d->pend_out, addr, &r)) {
            finish(d, r, -ENOENT, 0);
            ok(c);
        } else {
            fail(c, EINVAL); /* already completed: the caller reaps it */
        }
        break;
    }
    case USBDEVFS_REAPURB:
    case USBDEVFS_REAPURBNDELAY: {
        pump(d);
        urb_rec *r = g_queue_pop_head(&d->done);
        if (!r) {
            fail(c, d->gone ? ENODEV : EAGAIN);
            break;
        }
        UMockdevIoctlData *p = resolve(arg, 0, sizeof(gpointer));
        if (!p) {
            g_queue_push_head(&d->done, r); /* still to reap, if the client ever asks again */
            fail(c, EFAULT);
            break;
        }
        umockdev_ioctl_data_set_ptr(p, 0, r->urb);
        ok(c);
        d->reaps++;
        g_object_unref(p);
        if (r->buf)
            g_object_unref(r->buf);
        g_object_unref(r->urb);
        g_free(r);
        break;
    }
    default:
        fprintf(stderr, "test_link_usb: unhandled ioctl 0x%lx\n", req);
        handled = FALSE;
        break;
    }
    g_mutex_unlock(&d->lock);
    return handled;
}

static void drop_queue(GQueue *q)
{
    urb_rec *r;
    while ((r = g_queue_pop_head(q)) != NULL) {
        if (r->buf)
            g_object_unref(r->buf);
        g_object_unref(r->urb);
        g_free(r);
    }
}

/* A new board (power cycle) for the next run; URBs of an earlier (killed) client are dropped. */
static void dev_board(dev *d, const np_board_opts *bo)
{
    g_mutex_lock(&d->lock);
    drop_queue(&d->pend_out);
    drop_queue(&d->pend_in);
    drop_queue(&d->done);
    np_board_free(d->board);
    d->board = np_board_new(bo);
    d->gone_at = d->stall_at = d->kill_at = d->nak_at = 0;
    d->kill_sig = 0;
    d->gone = d->in_halted = d->stalled = d->killed = 0;
    g_mutex_unlock(&d->lock);
}

static dev *dev_new(const np_board_opts *bo)
{
    dev *d = g_new0(dev, 1);
    snprintf(d->serial, sizeof d->serial, "NP-0001");
    g_mutex_init(&d->lock);
    g_queue_init(&d->pend_out);
    g_queue_init(&d->pend_in);
    g_queue_init(&d->done);
    dev_board(d, bo);
    d->tb = umockdev_testbed_new();
    d->handler = umockdev_ioctl_base_new();
    g_signal_connect(d->handler, "handle-ioctl", G_CALLBACK(on_ioctl), d);
    GError *e = NULL;
    /* The handler first, so the node answers as soon as it exists. */
    if (!umockdev_testbed_attach_ioctl(d->tb, DEVNODE, d->handler, &e) ||
        !umockdev_testbed_add_from_string(d->tb, device_record, &e)) {
        fprintf(stderr, "umockdev: %s\n", e ? e->message : "?");
        exit(2);
    }
    return d;
}

static void dev_free(dev *d)
{
    umockdev_testbed_detach_ioctl(d->tb, DEVNODE, NULL);
    g_object_unref(d->handler);
    g_object_unref(d->tb);
    g_mutex_lock(&d->lock);
    drop_queue(&d->pend_out);
    drop_queue(&d->pend_in);
    drop_queue(&d->done);
    np_board_free(d->board);
    g_mutex_unlock(&d->lock);
    g_mutex_clear(&d->lock);
    g_free(d);
}

/* ------------------------------------------------------------------------- */
/* Running the command. */

typedef struct run {
    int status; /* exit status, or 128 + signal */
    char *out, *err;
    uint64_t board_records;
} run;

static char *slurp(const char *path)
{
    gchar *text = NULL;
    if (!g_file_get_contents(path, &text, NULL, NULL))
        text = g_strdup("");
    unlink(path);
    return text;
}

static void run_argv(dev *d, run *r, char **argv, int n);

/* noisepipe stream --device 1209:0001 ARGS... ; NULL-terminated. */
static void run_cli(dev *d, run *r, ...)
{
    char *argv[40];
    int n = 0;
    argv[n++] = (char *)NP_CLI;
    argv[n++] = (char *)"stream";
    argv[n++] = (char *)"--device";
    argv[n++] = (char *)"1209:0001";
    va_list ap;
    va_start(ap, r);
    for (char *a; n < 39 && (a = va_arg(ap, char *)) != NULL;)
        argv[n++] = a;
    va_end(ap);
    argv[n] = NULL;
    run_argv(d, r, argv, n);
}

static void run_argv(dev *d, run *r, char **argv, int n)
{
    char out[64], err[64];
    snprintf(out, sizeof out, "usb.%ld.out", (long)getpid());
    snprintf(err, sizeof err, "usb.%ld.err", (long)getpid());
    pid_t pid = np_child_start(argv, out, err);
    d->child = pid;
    int st;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
        ;
    d->child = 0;
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    r->out = slurp(out);
    r->err = slurp(err);
    g_mutex_lock(&d->lock);
    r->board_records = records(d);
    g_mutex_unlock(&d->lock);
    printf("$ noisepipe");
    for (int k = 1; k < n; k++)
        printf(" %s", argv[k]);
    printf("\n%s%s[exit %d; the emulated board took %llu records]\n", r->out, r->err, r->status,
           (unsigned long long)r->board_records);
}

static void run_free(run *r)
{
    g_free(r->out);
    g_free(r->err);
}

/* Verified ranges of a journal: vectors covered, and whether 0..n-1 each exactly once. */
static uint64_t journal_count(const char *path, uint64_t n, int *exactly_once)
{
    FILE *f = fopen(path, "r");
    uint8_t *seen = calloc((size_t)n, 1);
    uint64_t total = 0;
    int once = 1;
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        unsigned long long first, count, errs;
        if (line[0] != 'R' || !strchr(line, '\n') || sscanf(line, "R %llx %llx %llx", &first, &count, &errs) != 3)
            continue;
        for (uint64_t i = first; i < first + count && i < n; i++)
            once &= seen[i]++ == 0;
        total += count;
    }
    for (uint64_t i = 0; i < n; i++)
        once &= seen[i] == 1;
    if (f)
        fclose(f);
    free(seen);
    if (exactly_once)
        *exactly_once = once;
    return total;
}

static void journal_name(char *buf, size_t len, const char *what)
{
    snprintf(buf, len, "usb.%ld.%s.journal", (long)getpid(), what);
    unlink(buf);
}

static np_board_opts plain_board(void)
{
    np_board_opts o;
    memset(&o, 0, sizeof o);
    return o;
}

/* ------------------------------------------------------------------------- */
/* Cases. */

static int t_enumerate(void)
{
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", "1000", NULL);
    NP_CHECK(r.status == 0, "exit %d", r.status);
    NP_CHECK(strstr(r.out, "usb: endpoints 0x01/0x81, wMaxPacketSize 512") != NULL, "endpoints found from the descriptors");
    NP_CHECK(strstr(r.out, "In 1000 tests, no errors found") != NULL, "verdict");
    run_free(&r);
    run_cli(d, &r, "--unit", "classic3", "--random", "10", "--ep-in", "0x82", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "no bulk IN endpoint 0x82"), "exit %d: %s", r.status, r.err);
    run_free(&r);
    run_cli(d, &r, "--unit", "classic3", "--random", "10", "--interface", "1", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "no interface 1"), "exit %d: %s", r.status, r.err);
    run_free(&r);
    run_cli(d, &r, "--unit", "classic3", "--random", "10", "--ep-out", "1", "--ep-in", "0x81", "--interface", "0",
            "--in-flight", "2", NULL);
    NP_CHECK(r.status == 0, "explicit endpoints: exit %d", r.status);
    run_free(&r);
    dev_free(d);
    return 0;
}

static int t_stream(void)
{
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", "--seed", "5", NULL);
    NP_CHECK(r.status == 0, "exit %d", r.status);
    NP_CHECK(strstr(r.out, "In 200000 tests, no errors found in classic3") != NULL, "verdict");
    NP_CHECK(r.board_records == 200000, "board took %llu", (unsigned long long)r.board_records);
    printf("URBs: %llu submitted, %llu reaped, %llu discarded\n", (unsigned long long)d->submits,
           (unsigned long long)d->reaps, (unsigned long long)d->discards);
    run_free(&r);
    dev_free(d);
    return 0;
}

static int t_wrong_bit(void)
{
    np_board_opts bo = plain_board();
    bo.fault.kind = NP_BOARD_WRONG_BIT;
    bo.fault.at = 123457;
    bo.fault.bit = 0;
    dev *d = dev_new(&bo);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", NULL);
    NP_CHECK(r.status == 1, "exit %d", r.status);
    unsigned lines = 0;
    for (const char *p = r.out; (p = strstr(p, " => ")) != NULL; p++)
        lines++;
    NP_CHECK(lines == 1, "%u failure lines", lines);
    NP_CHECK(strstr(r.out, "vector 123457\n") != NULL, "the failing vector is named");
    NP_CHECK(strstr(r.out, "In 200000 tests, 1 error found in classic3") != NULL, "verdict");
    run_free(&r);
    dev_free(d);
    return 0;
}

static int t_not_found(void)
{
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    char *argv[] = { (char *)NP_CLI, (char *)"stream", (char *)"--device", (char *)"1209:9999", (char *)"--unit",
                     (char *)"classic3", (char *)"--random", (char *)"10", NULL };
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        execv(argv[0], argv);
        _exit(127);
    }
    int st;
    waitpid(pid, &st, 0);
    NP_CHECK(WIFEXITED(st) && WEXITSTATUS(st) == 2, "no such device: status %d", st);
    dev_free(d);
    return 0;
}

static int t_config_refused(void)
{
    np_board_opts bo = plain_board();
    bo.board_id = "classic3 board, one slot";
    bo.n_slots = 1;
    snprintf(bo.slot[0].unit, sizeof bo.slot[0].unit, "classic3");
    snprintf(bo.slot[0].cfg, sizeof bo.slot[0].cfg, "out_bits=8 s_frac=12 lerp_frac=11");
    dev *d = dev_new(&bo);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--config", "out_bits=10", "--random", "100", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "does not run classic3 out_bits=10") &&
                 strstr(r.err, "slot 0: classic3 out_bits=8 s_frac=12 lerp_frac=11"),
             "exit %d", r.status);
    run_free(&r);
    run_cli(d, &r, "--unit", "classic3", "--random", "100", NULL);
    NP_CHECK(r.status == 0, "the slot's own configuration: exit %d", r.status);
    run_free(&r);
    dev_free(d);
    return 0;
}

/*
 * --resume of journal, a run of n random classic3 vectors of which it holds
 * held, on d's board as it now is: exit 0 with the verdict, exactly the rest
 * sent, every vector once (*once). The records the board saw; what names the
 * case in the messages.
 */
static uint64_t resume_rest(dev *d, const char *journal, uint64_t n, uint64_t held, const char *what, int *once)
{
    char count[24], verdict[64];
    snprintf(count, sizeof count, "%llu", (unsigned long long)n);
    snprintf(verdict, sizeof verdict, "In %llu tests, no errors found", (unsigned long long)n);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", count, "--journal", journal, "--resume", NULL);
    NP_CHECK(r.status == 0, "%s resumed: exit %d", what, r.status);
    NP_CHECK(strstr(r.out, verdict), "%s resumed: verdict", what);
    NP_CHECK(r.board_records == n - held, "%s resumed: sent %llu, the journal held %llu of %llu", what,
             (unsigned long long)r.board_records, (unsigned long long)held, (unsigned long long)n);
    journal_count(journal, n, once);
    NP_CHECK(*once, "%s: the journal does not hold every vector exactly once", what);
    uint64_t sent = r.board_records;
    run_free(&r);
    return sent;
}

/*
 * A fault mid-stream, then --resume on a healthy board: the fault's message
 * and status, nothing verified lost, nothing sent twice, every vector once.
 */
static void fault_then_resume(const char *name, np_board_fault bf, uint64_t gone_at, uint64_t stall_at,
                              uint64_t nak_at, const char *timeout, const char *words)
{
    enum { N = 200000 };
    np_board_opts bo = plain_board();
    bo.fault = bf;
    dev *d = dev_new(&bo);
    d->gone_at = gone_at;
    d->stall_at = stall_at;
    d->nak_at = nak_at;
    char journal[128];
    journal_name(journal, sizeof journal, name);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", "--journal", journal, "--timeout", timeout, NULL);
    NP_CHECK(r.status == 1, "%s: exit %d", name, r.status);
    NP_CHECK(strstr(r.err, words) != NULL, "%s: message lacks '%s'", name, words);
    NP_CHECK(strstr(r.out, "INCOMPLETE") && strstr(r.out, "--resume"), "%s: verdict says incomplete", name);
    if (stall_at)
        NP_CHECK(d->clear_halts_after_stall >= 1, "stall: the host did not clear the halt");
    int once;
    uint64_t held = journal_count(journal, N, &once);
    NP_CHECK(held > 0 && held < N, "%s: journal holds %llu", name, (unsigned long long)held);
    run_free(&r);

    np_board_opts healthy = plain_board();
    dev_board(d, &healthy);
    resume_rest(d, journal, N, held, name, &once);
    unlink(journal);
    dev_free(d);
}

/*
 * The faults fault_then_resume runs, one CTest case each: the board's own
 * fault, the transfer at which the device disappears, stalls its IN endpoint
 * or NAKs OUT forever (0: never), the --timeout and the words the run must say.
 * t_timeout_out: the board stops taking OUT data, so libusb's transfer
 * time-out or the watchdog ends the run.
 */
static const struct resume_fault {
    const char *name;
    np_board_fault bf;
    uint64_t gone_at, stall_at, nak_at;
    const char *timeout, *words;
} resume_faults[] = {
    { "disappear", { NP_BOARD_OK, 0, 0 }, 100000, 0, 0, "10", "the board disappeared (LIBUSB_" },
    { "timeout", { NP_BOARD_SILENT, 100000, 0 }, 0, 0, 0, "1", "timeout: the board sent nothing for 1.0 s" },
    { "timeout_out", { NP_BOARD_OK, 0, 0 }, 0, 0, 100000, "1", "timeout: the board has taken no data for 1.0 s" },
    { "stall", { NP_BOARD_OK, 0, 0 }, 0, 100000, 0, "10", "endpoint 0x81 (IN) stalled (LIBUSB_TRANSFER_STALL" },
    { "corrupt", { NP_BOARD_CORRUPT, 100000, 0 }, 0, 0, 0, "10", "corrupted frame from the board" },
    { "short", { NP_BOARD_SHORT, 100000, 0 }, 0, 0, 0, "10", "short frame from the board" },
};

static int resume_fault_case(const char *name)
{
    for (size_t i = 0; i < sizeof resume_faults / sizeof resume_faults[0]; i++) {
        const struct resume_fault *c = &resume_faults[i];
        if (strcmp(c->name, name) == 0) {
            fault_then_resume(c->name, c->bf, c->gone_at, c->stall_at, c->nak_at, c->timeout, c->words);
            return 0;
        }
    }
    NP_CHECK(0, "no resume fault '%s'", name);
    return 1;
}

static int t_disappear(void) { return resume_fault_case("disappear"); }
static int t_timeout(void) { return resume_fault_case("timeout"); }
static int t_timeout_out(void) { return resume_fault_case("timeout_out"); }
static int t_stall(void) { return resume_fault_case("stall"); }
static int t_corrupt(void) { return resume_fault_case("corrupt"); }
static int t_short(void) { return resume_fault_case("short"); }

/*
 * Item 3 of issue 11: the journal is bound to its target. An emulator's
 * journal does not count for a board; one board's (serial NP-0001) not for
 * another's (NP-0002); a run that cannot open its board never touches the
 * journal, not even with --force.
 */
static int t_journal_target(void)
{
    enum { N = 200000 };
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    char journal[128];
    journal_name(journal, sizeof journal, "target");
    run r;
    char *emu[] = { (char *)NP_CLI, (char *)"stream", (char *)"--emulate", (char *)"--unit", (char *)"classic3",
                    (char *)"--random", (char *)"200000", (char *)"--journal", journal, NULL };
    run_argv(d, &r, emu, 9);
    NP_CHECK(r.status == 0, "emulator run: exit %d", r.status);
    run_free(&r);
    gchar *emu_journal = NULL;
    gsize emu_len = 0;
    g_file_get_contents(journal, &emu_journal, &emu_len, NULL);
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", "--journal", journal, "--resume", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "'target=emulator', this run is 'target=usb 1209:0001 serial NP-0001'") &&
                 strstr(r.err, "another target"),
             "the emulator's journal for a board: exit %d", r.status);
    NP_CHECK(r.board_records == 0, "nothing streamed: %llu", (unsigned long long)r.board_records);
    NP_CHECK(!strstr(r.out, "no errors found"), "no verdict");
    run_free(&r);
    /* Without --resume or --force: refused, and the file is as it was. */
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", "--journal", journal, NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "--force"), "exit %d", r.status);
    run_free(&r);
    /* --force, but the board is not there: exit 2, the journal untouched. */
    char *gone[] = { (char *)NP_CLI, (char *)"stream", (char *)"--device", (char *)"1209:9999", (char *)"--unit",
                     (char *)"classic3", (char *)"--random", (char *)"200000", (char *)"--journal", journal,
                     (char *)"--force", NULL };
    run_argv(d, &r, gone, 11);
    NP_CHECK(r.status == 2 && strstr(r.err, "no USB device 1209:9999"), "exit %d", r.status);
    gchar *now = NULL;
    gsize now_len = 0;
    g_file_get_contents(journal, &now, &now_len, NULL);
    NP_CHECK(now && emu_journal && now_len == emu_len && memcmp(now, emu_journal, emu_len) == 0,
             "a run whose board did not open changed the journal");
    g_free(now);
    g_free(emu_journal);
    run_free(&r);
    /* --force with the board open: a new journal, bound to this board; a fault part way. */
    bo.fault.kind = NP_BOARD_SILENT;
    bo.fault.at = 100000;
    dev_board(d, &bo);
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", "--journal", journal, "--force", "--timeout", "1", NULL);
    NP_CHECK(r.status == 1 && strstr(r.out, "target: usb 1209:0001 serial NP-0001"), "exit %d", r.status);
    int once;
    uint64_t held = journal_count(journal, N, &once);
    NP_CHECK(held > 0 && held < N, "held %llu", (unsigned long long)held);
    run_free(&r);
    /* Another board (serial NP-0002) may not continue it... */
    np_board_opts healthy = plain_board();
    dev_board(d, &healthy);
    snprintf(d->serial, sizeof d->serial, "NP-0002");
    run_cli(d, &r, "--unit", "classic3", "--random", "200000", "--journal", journal, "--resume", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "serial NP-0001', this run is 'target=usb 1209:0001 serial NP-0002'"),
             "another board: exit %d", r.status);
    NP_CHECK(r.board_records == 0, "nothing streamed");
    run_free(&r);
    /* ...the same board does, sending exactly the rest. */
    snprintf(d->serial, sizeof d->serial, "NP-0001");
    resume_rest(d, journal, N, held, "the same board", &once);
    unlink(journal);
    dev_free(d);
    return 0;
}

/* SIGINT mid-stream through USB: exit 130, the note names the journal and --resume; the resume is exact. */
static int t_interrupt(void)
{
    enum { N = 300000 };
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    char journal[128];
    journal_name(journal, sizeof journal, "sigint");
    d->kill_at = 150000;
    d->kill_sig = SIGINT;
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", "300000", "--journal", journal, NULL);
    NP_CHECK(r.status == 130, "status %d", r.status);
    NP_CHECK(strstr(r.err, "interrupted by SIGINT") && strstr(r.err, journal) && strstr(r.err, "--resume"),
             "the note: %s", r.err);
    int once;
    uint64_t held = journal_count(journal, N, &once);
    run_free(&r);
    dev_board(d, &bo);
    resume_rest(d, journal, N, held, "SIGINT", &once);
    unlink(journal);
    dev_free(d);
    return 0;
}

/* Section 10: a board that answers HELLO with ERROR BAD_VERSION: the message, exit 2 (not a time-out). */
static int t_hello_bad_version(void)
{
    np_board_opts bo = plain_board();
    bo.version = 2;
    dev *d = dev_new(&bo);
    run r;
    char journal[128];
    journal_name(journal, sizeof journal, "badver");
    run_cli(d, &r, "--unit", "classic3", "--random", "1000", "--journal", journal, NULL);
    NP_CHECK(r.status == 2, "exit %d", r.status);
    NP_CHECK(access(journal, F_OK) != 0, "the new journal, holding nothing, is not left behind");
    NP_CHECK(strstr(r.err, "the board refused HELLO: ERROR BAD_VERSION") && strstr(r.err, "speaks protocol version 2"),
             "message: %s", r.err);
    NP_CHECK(!strstr(r.err, "sent nothing"), "reported as a time-out");
    run_free(&r);
    dev_free(d);
    return 0;
}

/* Section 4.1: a board at the smallest max_payload (292) works; below it, exit 2 with the documented message. */
static int t_min_payload(void)
{
    np_board_opts bo = plain_board();
    bo.max_payload = 292;
    dev *d = dev_new(&bo);
    run r;
    run_cli(d, &r, "--unit", "classic3", "--random", "20000", NULL);
    NP_CHECK(r.status == 0 && strstr(r.out, "max payload 292; 36 vectors per frame") &&
                 strstr(r.out, "In 20000 tests, no errors found"),
             "292: exit %d", r.status);
    run_free(&r);
    bo.max_payload = 64;
    dev_board(d, &bo);
    run_cli(d, &r, "--unit", "classic3", "--random", "20000", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "announces max_payload 64 bytes, less than the 292 the protocol requires"),
             "64: exit %d", r.status);
    run_free(&r);
    dev_free(d);
    return 0;
}

/* SIGKILL at a random record, then --resume: every vector verified exactly once. */
static int t_kill_resume(void)
{
    enum { N = 300000 };
    uint64_t seed = np_child_seed();
    np_rng rng;
    np_rng_seed(&rng, seed);
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    char journal[128];
    journal_name(journal, sizeof journal, "kill");
    for (int trial = 0; trial < 3; trial++) {
        unlink(journal);
        dev_board(d, &bo);
        uint64_t kill_at = 1 + np_rng_below(&rng, N - 1);
        d->kill_at = kill_at;
        run r;
        run_cli(d, &r, "--unit", "classic3", "--random", "300000", "--journal", journal, NULL);
        NP_CHECK(r.status == 128 + SIGKILL, "trial %d: status %d", trial, r.status);
        int once;
        uint64_t held = journal_count(journal, N, &once);
        run_free(&r);
        dev_board(d, &bo);
        char what[32];
        snprintf(what, sizeof what, "trial %d", trial);
        uint64_t sent = resume_rest(d, journal, N, held, what, &once);
        printf("trial %d: killed near record %llu with %llu journaled; resume sent %llu; every vector once: %s\n",
               trial, (unsigned long long)kill_at, (unsigned long long)held, (unsigned long long)sent,
               once ? "yes" : "NO");
    }
    unlink(journal);
    dev_free(d);
    return 0;
}

/* The "link:" and "host CPU:" lines of a run. */
typedef struct figures {
    double vps, mbs, host_ns;
} figures;

static int parse_figures(const char *out, figures *f)
{
    const char *l = strstr(out, "\nlink: ");
    const char *c = strstr(out, "\nhost CPU: ");
    unsigned long long n;
    double t, mo, mi, cs;
    memset(f, 0, sizeof *f);
    return l && c &&
           sscanf(l, "\nlink: %llu vectors in %lf s: %lf vectors/s; %lf MB/s out, %lf MB/s in (%lf", &n, &t,
                  &f->vps, &mo, &mi, &f->mbs) == 6 &&
           sscanf(c, "\nhost CPU: %lf s, %lf ns", &cs, &f->host_ns) == 2;
}

static double self_cpu(int who)
{
    struct rusage ru;
    getrusage(who, &ru);
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 + (double)ru.ru_stime.tv_sec +
           (double)ru.ru_stime.tv_usec * 1e-6;
}

/*
 * The benchmark: n vectors of classic3 through the emulated USB device, and
 * the same through the in-process emulator; prints vectors/s, MB/s and the
 * host's CPU time per vector (as `noisepipe stream` measured them), and the
 * device side's CPU (umockdev's ioctl handling and the board emulator, in
 * this process).
 */
static int bench_n(uint64_t n)
{
    np_board_opts bo = plain_board();
    dev *d = dev_new(&bo);
    char count[32], want[96];
    snprintf(count, sizeof count, "%llu", (unsigned long long)n);
    snprintf(want, sizeof want, "In %llu tests, no errors found in classic3", (unsigned long long)n);
    run r, e;
    double c0 = self_cpu(RUSAGE_SELF), t0 = np_now();
    run_cli(d, &r, "--unit", "classic3", "--random", count, NULL);
    double wall = np_now() - t0, dev_cpu = self_cpu(RUSAGE_SELF) - c0;
    NP_CHECK(r.status == 0 && strstr(r.out, want), "exit %d", r.status);
    NP_CHECK(r.board_records == n, "board took %llu", (unsigned long long)r.board_records);
    char *argv[] = { (char *)NP_CLI, (char *)"stream", (char *)"--emulate", (char *)"--unit", (char *)"classic3",
                     (char *)"--random", count, NULL };
    run_argv(d, &e, argv, 7);
    NP_CHECK(e.status == 0 && strstr(e.out, want), "--emulate: exit %d", e.status);
    figures fu, fe;
    NP_CHECK(parse_figures(r.out, &fu) && parse_figures(e.out, &fe), "figures not found in the output");
    printf("\n== figures: %llu classic3 vectors, 8 bytes out + 4 back each ==\n", (unsigned long long)n);
    printf("through the emulated USB device (libusb async bulk, umockdev, board emulator):\n");
    printf("  %.0f vectors/s, %.2f MB/s (both ways, framing included)\n", fu.vps, fu.mbs);
    printf("  host CPU %.0f ns per vector (noisepipe stream, streaming phase)\n", fu.host_ns);
    printf("  device side CPU %.0f ns per vector (umockdev ioctl handling + cycle-accurate board emulator)\n",
           dev_cpu / (double)n * 1e9);
    printf("  whole run %.2f s (process start, vector generation, USB setup included)\n", wall);
    printf("through the in-process emulator (--emulate, no USB):\n");
    printf("  %.0f vectors/s, %.2f MB/s; host CPU %.0f ns per vector\n", fe.vps, fe.mbs, fe.host_ns);
    run_free(&r);
    run_free(&e);
    dev_free(d);
    return 0;
}

/* Acceptance: 10^6 vectors through the emulated device verify with no error; the figures. */
static int t_stream_1e6(void) { return bench_n(1000000); }

static const np_test_case cases[] = {
    { "enumerate", t_enumerate },
    { "stream", t_stream },
    { "stream_1e6", t_stream_1e6 },
    { "wrong_bit", t_wrong_bit },
    { "not_found", t_not_found },
    { "config_refused", t_config_refused },
    { "disappear", t_disappear },
    { "timeout", t_timeout },
    { "timeout_out", t_timeout_out },
    { "stall", t_stall },
    { "corrupt", t_corrupt },
    { "short", t_short },
    { "kill_resume", t_kill_resume },
    { "journal_target", t_journal_target },
    { "interrupt", t_interrupt },
    { "hello_bad_version", t_hello_bad_version },
    { "min_payload", t_min_payload },
    { NULL, NULL },
};

int np_test_failures = 0;

/* umockdev complains when a client is killed with its socket open: expected in kill_resume. */
static void log_filter(const gchar *domain, GLogLevelFlags level, const gchar *msg, gpointer user)
{
    if (msg && strstr(msg, "Destroying IoctlClient with open stream"))
        return;
    g_log_default_handler(domain, level, msg, user);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        for (const np_test_case *c = cases; c->name; c++)
            puts(c->name);
        return 0;
    }
    const char *pre = getenv("LD_PRELOAD");
    if (!pre || !strstr(pre, "umockdev-preload")) {
        fprintf(stderr, "test_link_usb: run me under umockdev-wrapper\n");
        return 2;
    }
    g_log_set_default_handler(log_filter, NULL);
    if (strcmp(argv[1], "bench") == 0 && argc > 2) {
        bench_n(strtoull(argv[2], NULL, 0));
        return np_test_failures ? 1 : 0;
    }
    for (const np_test_case *c = cases; c->name; c++)
        if (strcmp(c->name, argv[1]) == 0) {
            int rc = c->fn();
            if (np_test_failures)
                fprintf(stderr, "%s: %d check(s) failed\n", c->name, np_test_failures);
            return rc || np_test_failures ? 1 : 0;
        }
    fprintf(stderr, "unknown case '%s'\n", argv[1]);
    return 2;
}
