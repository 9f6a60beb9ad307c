/* base_proc.h - an external program (a shell command line) run to its
 * end, to a time limit, or to a signal, whichever comes first.
 *
 * The command runs in a process group of its own (so a tool's own
 * children, Yosys's ABC among them, go with it), its standard input from
 * /dev/null. On the time limit, or when SIGINT, SIGTERM or SIGHUP reach
 * shadesim while it runs, the whole group gets SIGTERM, then SIGKILL two
 * seconds later if it is still there, and the call returns: the caller
 * removes what it made (a temporary folder), then, after a signal, calls
 * base_proc_reraise so that shadesim dies by that signal as it would have
 * (base_out's registered temporaries removed on the way).
 *
 * A progress line on stderr, rewritten in place about once a second
 * ("VERB: STEP, N s"), is for a terminal only: the caller asks for it
 * when stderr is one, and it is erased before the call returns.
 */
#ifndef BASE_PROC_H
#define BASE_PROC_H
#include <stddef.h>

enum { BASE_PROC_DONE = 0, BASE_PROC_TIMEOUT = 1, BASE_PROC_SIGNAL = 2, BASE_PROC_ERROR = 3 };

typedef struct base_proc {
    const char *verb;       /* for the progress line: "synth" */
    const char *step;       /* what runs: "yosys", "sta", "nextpnr" */
    const char *dir;        /* the folder it runs in (NULL: ours) */
    /* the step's detail for the progress line (e.g. the pass a log names),
     * written into buf; NULL: none */
    void (*detail)(void *ctx, char *buf, size_t len);
    void *ctx;
    double start;           /* base_proc_now() when the whole job began */
    double limit_s;         /* seconds from start; <= 0: no limit */
    int progress;           /* 1: the progress line (stderr is a terminal) */
    /* results */
    int status;             /* the exit status (BASE_PROC_DONE), or the signal that ended it + 128 */
    int signal;             /* BASE_PROC_SIGNAL: the signal shadesim received */
} base_proc;

/* Seconds on a monotonic clock. */
double base_proc_now(void);
/* Run `sh -c cmd`. BASE_PROC_DONE (p->status set), BASE_PROC_TIMEOUT,
 * BASE_PROC_SIGNAL (p->signal set) or BASE_PROC_ERROR (no process could be
 * made; message in err). */
int base_proc_run(const char *cmd, base_proc *p, char *err, size_t errlen);
/* Remove folder dir and everything in it (links not followed): a
 * temporary folder's end. 0, or -1 when something stayed. */
int base_proc_rmtree(const char *dir);
/* The signal that stopped the last base_proc_run of this process (0:
 * none): for a caller whose callee ran the tools, to clean up and then
 * base_proc_reraise it. */
int base_proc_signal(void);
/* Die by sig as shadesim's own handlers (base_out_install_signals) would
 * have made it: the handlers in place before base_proc_run get it. */
_Noreturn void base_proc_reraise(int sig);
/* Signals held: from base_proc_hold until base_proc_release, SIGINT,
 * SIGTERM and SIGHUP are only recorded (base_proc_signal gives the first),
 * for a caller that owns what a signal must not leave behind, a temporary
 * folder with a tool's files: it looks at base_proc_signal at its own
 * points, removes what it made, and calls base_proc_reraise. A
 * base_proc_run inside starts no tool once a signal is recorded, and one
 * that arrives while the tool runs ends it as always. Not nested. */
void base_proc_hold(void);
void base_proc_release(void);
#endif
