/* cli_man.h - the manual page shadesim.1, generated from the verb table
 * (cli_verbs) and each verb's own --help text, so that the man page and
 * --help can never disagree. `shadesim --man` prints it; `make install`
 * installs it.
 */
#ifndef CLI_MAN_H
#define CLI_MAN_H
#include <stdio.h>

/* Write the roff source of shadesim(1) to f. version: the string that
 * `shadesim --version` prints. 0, or -1 when a verb's help could not be
 * captured (message on stderr). Deterministic: no date in the page. */
int cli_man(FILE *f, const char *version);
#endif
