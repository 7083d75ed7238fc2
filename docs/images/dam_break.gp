# Draws docs/images/dam_break.png. In a folder holding the states.csv and particles.csv of
# `anyphys run docs/images/dam_break.json --steps 60 --out states.csv --particles particles.csv`,
# run `python3 dam_break_data.py` (this folder) and then `gnuplot dam_break.gp`.
set terminal pngcairo size 1500,420 font "Sans,11"
set output "dam_break.png"
set multiplot layout 1,3 title "Dam break with three crates (anyphys run --particles, native, planar, 640 particles, 60 Hz)"
set xrange [-0.1:2.1]; set yrange [-0.1:0.9]; set size ratio -1
set cbrange [0:3]; set cblabel "speed (m/s)"; set palette defined (0 "#08306b", 1 "#2171b5", 2 "#6baed6", 3 "#deebf7")
unset colorbox
do for [s in "0 24 48"] {
  set title sprintf("t = %.1f s", s/60.0)
  set object 1 rect from -0.1,-0.1 to 2.1,0 fc rgb "#999999" fs solid noborder
  plot sprintf("p%s.dat", s) u 1:2:3 w p pt 7 ps 0.45 lc palette notitle, \
       sprintf("c%s.dat", s) u 1:2 w filledcurves closed lc rgb "#c07a2c" notitle, \
       sprintf("c%s.dat", s) u 1:2 w l lc rgb "#5a3510" lw 1.5 notitle
}
unset multiplot
