# Partial cuts on the beam (partial.csv, examples/05_paulus_study.cpp --only partial): the opening
# |[u]| along a line through the front, against the distance ahead of the front.
set terminal pngcairo size 1400,500 font ",11"
set output 'partial.png'
set datafile separator ','
set datafile missing NaN
set grid
set xlabel 'distance ahead of the front along the line (mm)'
set ylabel 'opening |[u]| (mm)'
pick(c, t) = (strcol(1) eq c && strcol(2) eq t) ? 1000 * $4 : NaN
set multiplot layout 1,3
titles = "'half disc R = 12 mm (line y = 30 mm)' 'plane, front x = 15 + 4 sin(2 pi y / 60) mm (line y = 15 mm)' 'declining sine blade, front x = 15 mm (line y = 15 mm)'"
do for [i = 1:3] {
  c = word("half_disc sine_front declining_sine", i)
  set title word(titles, i)
  plot 'partial.csv' using (pick(c, "heaviside")):(1000*$5) with lines lw 2 title 'Heaviside only', \
       '' using (pick(c, "geometric")):(1000*$5) with lines lw 2 title 'geometric branch'
}
unset multiplot
