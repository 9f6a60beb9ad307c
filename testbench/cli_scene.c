/* cli_scene.c - shadesim scene (being built). */
#include "testbench/cli.h"

int cli_scene(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_usage_error("scene: not built yet");
}
