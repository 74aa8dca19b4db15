# pipelines/error_vs_time.gp - error against run time (log-log) from a table of pipelines/table.sh.
#   gnuplot -e "table='T.tsv'; out='E.png'; name='CASE'" pipelines/error_vs_time.gp
# Columns of the table: dp_m particles steps run_time_s error verdict; each point is labelled
# with its dp. Rows whose error is not a number (a failed run) are skipped by gnuplot.
set terminal pngcairo size 800,560 noenhanced font ",11"
set output out
set datafile separator "\t"
set datafile commentschars "#"
set logscale xy
set grid
set key top right
set title name . ": error against run time"
set xlabel "vres-run wall-clock time (s)"
set ylabel "error (see the table's header)"
set offsets graph 0.08, graph 0.08, graph 0.08, graph 0.08
plot table using 4:5 with linespoints pointtype 7 pointsize 1.3 title "single resolution", \
     table using 4:5:(sprintf("dp %g m\n%d particles", $1, $2)) with labels offset char 0.8,char 1.4 left notitle
