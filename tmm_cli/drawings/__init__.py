"""The drawings the report and the A1 sheets both draw, as public functions onto a canvas
(the report's SVG canvas, report.svgdraw.Canvas, or a sheet's, sheets.prims.PrimCanvas):

* drawings.plans: a velocity or acceleration plan with its scale bar (draw_plan);
* drawings.forces: a structural group with its loads (group_panel), its force polygon
  (polygon_panel), Zhukovsky's lever (lever_panel), the groups of a position (position_rows);
* drawings.mesh: the wheels of a gear pair and the points of its line of action;
* drawings.train: a drive's gear train -- its scheme, the linear-velocity picture beside it
  and the angular-velocity plan (scheme_and_picture, angular_plan);
* drawings.words: what they write, in the drawing's language (Words).

Neither the report's sections nor the sheets reach into each other's private names: both
call these."""
