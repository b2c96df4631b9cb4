/* platform/cmd.h — the subcommands of the bitrain program.
 * Each takes the arguments after its name and returns the process exit code
 * (0 ok, 1 error with a message on stderr, 2 usage). One file per command:
 * platform/cmd_<name>.c. */
#ifndef BR_CMD_H
#define BR_CMD_H

int cmd_info(int argc, char **argv);      /* bitrain info [--json] [--merge] FILE... */
int cmd_hillshade(int argc, char **argv); /* bitrain hillshade IN... -o OUT.png */
int cmd_run(int argc, char **argv);       /* bitrain run [IN...]: the default job of `make run` */
int cmd_mesh(int argc, char **argv);      /* bitrain mesh IN... --max-error M -o out.{obj,ply,stl} */
int cmd_render(int argc, char **argv);    /* bitrain render IN... -o out.png ... */
int cmd_bench(int argc, char **argv);     /* bitrain bench --scene peer ... */
int cmd_bench_default(int argc, char **argv); /* bitrain bench --scene default ... (bench_default.c) */
int cmd_bench_board(int argc, char **argv);   /* bitrain bench [--scene all]: the board table (bench_board.c) */
int cmd_view(int argc, char **argv);      /* bitrain view IN...: SDL2 window */

#endif
