# Written by peensim almen-fit; rerun from this directory: gnuplot almen-fit-usp-example.gp
if (!exists("out")) out = 'almen-fit-usp-example.png'
set terminal pngcairo enhanced size 900,600 font 'sans,11'
set output out
set datafile separator ','
set grid
set title 'Saturation curve: usp-example.csv'
set xlabel 'exposure (s)'
set ylabel 'arc height (mm)'
set xrange [0:413.99999999999994]
set yrange [0:*]
set key bottom right
set samples 400
h2P(x) = x <= 0 ? 0 : 0.25092092543013633 * (1 - exp(-0.017894977703183573 * x**1))
h3P(x) = x <= 0 ? 0 : 0.25087766522990185 * (1 - exp(-0.017823699679229768 * x**1.0010857102060353))
set arrow from 128.67214093172123, graph 0 to 128.67214093172123, first 0.22582883288712272 nohead dt 2
set arrow from 257.34428186344246, graph 0 to 257.34428186344246, first 0.24841171617583502 nohead dt 3
set label 'T = 128.7 s, intensity 0.2258 mm (0.0089A)' at 128.67214093172123, first 0.22582883288712272 offset 1,-1.2
set label '2T' at 257.34428186344246, graph 0.04 offset 0.5,0
plot 'almen-fit-usp-example_points.csv' using 1:2 with points pt 7 ps 1.4 lc rgb '#202020' title 'measured', h2P(x) with lines lw 2 lc rgb '#3070b0' title '2P fit (used)', h3P(x) with lines lw 2 lc rgb '#c05020' dt 2 title '3P fit'
