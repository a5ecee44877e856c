// A part peensim never shipped, for `peensim new`'s tests: an L bracket with a bolt hole and a
// gusset, modelled off the origin (its corner at x = 40, y = -15 mm), in mm. Made with
//   openscad -o bracket.stl bracket.scad   (OpenSCAD 2021.01, Debian 12)
$fn = 24;
translate([40, -15, 5]) difference() {
    union() {
        cube([30, 20, 4]);                 // the base plate
        cube([4, 20, 25]);                 // the upright
        translate([4, 8, 4]) rotate([90, 0, 0]) translate([0, 0, -4])
            linear_extrude(4) polygon([[0, 0], [12, 0], [0, 12]]);  // the gusset
    }
    translate([20, 10, -1]) cylinder(r = 3, h = 6);            // the bolt hole in the base
    translate([-1, 10, 17]) rotate([0, 90, 0]) cylinder(r = 2.5, h = 6);  // and in the upright
}
