# Written by peensim trade; rerun from this directory: gnuplot trade-rod.gp
if (!exists("out")) out = 'trade-rod.png'
set terminal pngcairo enhanced size 1000,700 font 'sans,10'
set output out
set datafile separator ','
set grid
set logscale xy
set title 'rod-soft.yaml: error against wall time per accuracy knob'
set xlabel 'wall time of the run (s)'
set ylabel '|error| against the reference (%)'
set key outside right
set arrow from 4.01975, graph 0 to 4.01975, graph 1 nohead dt 2
set arrow from graph 0, first 2.28176 to graph 1, first 2.28176 nohead dt 3 lc 'gray'
set label 'noise: 3 SE of the reference rate' at graph 0.02, first 2.28176 offset 0,0.7 textcolor 'gray40'
set label 'reference' at 4.01975, graph 0.97 right offset -0.5,0
file = 'trade-rod.csv'
plot file using 1:2 with points pt 7 ps 1.3 title 'impact rate', \
     file using 1:3 with points pt 5 ps 1.2 title 'mean v_n', \
     file using 1:4 with points pt 9 ps 1.3 title 'p90 v_n', \
     file using 1:5 with points pt 13 ps 1.3 title 'coverage', \
     file using 1:2:6 with labels left offset 1,0 font 'sans,8' notitle
