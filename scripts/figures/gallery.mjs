// What docs/FIGURES.md shows per figure: the paper's words (quoted from the
// paper's text; the PDF extraction's lost spaces restored), the sentence that
// quotes our measured values (each read from the run's values.jsonl through
// `v`, never typed here), and the pictures with their fixed camera. The scenes
// themselves are the Catch2 tests named in `test` (tests/figure_record.h is
// how they hand their meshes and values over).
//
// Picture options: `mesh` (a recorded mesh name), `caption`; per figure:
// `direction` (camera from the frame's centre towards it), `up`, `frame`
// ('all': one sphere around every picture's mesh, so sizes compare; 'selection':
// around the selected vertices of the first picture; 'own': per picture),
// `flat` (flat shading, for the spool's sharp rims), `wireframe`.

const SPOOL = { direction: [0.35, 0.25, 1], up: [1, 0, 0], flat: true, frame: 'all' };

/** v(key) reads a measured value; fixed(x, digits) formats it. */
const fixed = (x, digits) => x.toFixed(digits);
const METHOD_NAMES = { linear: 'linear', arap: 'ARAP', anarap: 'AnARAP', andefgrad: 'AnDefGrad' };
const pct = (ratio, target) => `${ratio > target ? '+' : ''}${((ratio / target - 1) * 100).toFixed(1)} %`;

export const FIGURES = [
  {
    id: '1',
    title: 'Quadruped: a leg elongated, the body stays',
    test: 'tests/test_paper_figures.cpp, "fig. 1: ..."',
    scene: 'closed/cat-low-resolution.obj; the lowest foot\'s leg (up to 0.3 of the height, 0.12 of the diagonal ' +
      'around it) stretched by AnARAP, su 1.5 along y.',
    claim: 'Fig. 1: "The original model (right) was edited part-wise to change shape characteristics, such as the ' +
      'length and thickness of legs, body, ears, or tail (left)."',
    measured: (v) => `the selected leg's height ×${fixed(v('1.anarap.leg_height_ratio'), 2)}; the upper body ` +
      `(above 0.6 of the height) moves ${fixed(v('1.anarap.body_motion'), 4)} of the diagonal on average.`,
    view: { direction: [0.25, 0.1, 1], up: [0, 1, 0], frame: 'all' },
    pictures: [
      { mesh: '1-rest', caption: 'rest, selection in orange' },
      { mesh: '1-anarap', caption: 'AnARAP, su 1.5 along y' },
    ],
  },
  {
    id: '2',
    title: 'Torus: an elongated part, triangle sizes across the selection border',
    test: 'tests/test_paper_figures.cpp, "fig. 2: ..."',
    scene: 'closed/torus.obj; a sphere of 0.25 of the diagonal around the outermost point, su 1.6 along the big ' +
      'circle. Heat map: the app\'s area change (log2 of the one-ring area ratio; full colour at ×2).',
    claim: 'Fig. 2: "While the deformation gradient based method exhibits a high discontinuity of triangle sizes, ' +
      'the deformation using anisotropic ARAP deformation is distributed more globally over the selection border."',
    measured: (v) => `mean jump of log(area ratio) between the triangles either side of the selection border: ` +
      `AnARAP ${fixed(v('2.anarap.border_jump'), 3)}, AnDefGrad ${fixed(v('2.andefgrad.border_jump'), 3)}.`,
    view: { direction: [0.2, 1, 0.6], up: [0, 1, 0], frame: 'all', wireframe: true },
    pictures: [
      { mesh: '2-rest', caption: 'rest, selection' },
      { mesh: '2-andefgrad', caption: 'AnDefGrad, area change' },
      { mesh: '2-anarap', caption: 'AnARAP, area change' },
    ],
  },
  {
    id: '4',
    title: 'Shear of the spool\'s top',
    test: 'tests/test_figures_post.cpp, "fig. 4: ..."',
    scene: 'closed/spool.off (the MANIFEST\'s stand-in for the post; its axis is x, drawn upwards); the upper half ' +
      'sheared along y, h = 0.5.',
    claim: 'Fig. 4: "The organic appearance of ARAP is visible. The modified deformation gradient method gives more ' +
      'control. The orange regions are involved in the deformation while the blue ones are unaffected."',
    measured: (v) => `the top moves along the shear by ${fixed(v('4.anarap.top_shift'), 3)} (AnARAP) / ` +
      `${fixed(v('4.andefgrad.top_shift'), 3)} (AnDefGrad) of the height; the bottom 30 % moves ` +
      `${fixed(v('4.anarap.bottom_motion'), 4)} / ${fixed(v('4.andefgrad.bottom_motion'), 4)}.`,
    view: SPOOL,
    pictures: [
      { mesh: '4-rest', caption: 'rest, selection' },
      { mesh: '4-anarap', caption: 'AnARAP, shear 0.5 along y' },
      { mesh: '4-andefgrad', caption: 'AnDefGrad, shear 0.5 along y' },
    ],
  },
  {
    id: '5',
    title: 'Local rotation of the spool\'s top: a hook',
    test: 'tests/test_figures_post.cpp, "fig. 5: ..."',
    scene: 'closed/spool.off; the top 40 % (x above 0.6 of the height), every element turned 30° about z.',
    claim: 'Fig. 5: "The post (left) is rotated locally at the selected vertices to become a hook. The AnARAP ' +
      'approach (middle) exhibits more global deformation while AnDefGrad (right) has more local control."',
    measured: (v) => `the upper flange's rim tilts ${fixed(v('5.anarap.top_tilt'), 1)}° (AnARAP) / ` +
      `${fixed(v('5.andefgrad.top_tilt'), 1)}° (AnDefGrad) towards +y, the base rim ` +
      `${fixed(v('5.anarap.base_tilt'), 2)}° / ${fixed(v('5.andefgrad.base_tilt'), 2)}°; the top moves ` +
      `${fixed(v('5.anarap.top_shift_y'), 3)} / ${fixed(v('5.andefgrad.top_shift_y'), 3)} of the height along +y ` +
      `(along z: ${fixed(v('5.anarap.top_shift_z'), 3)} / ${fixed(v('5.andefgrad.top_shift_z'), 3)}). ` +
      `How far the edit reaches below the selection: change of shape (RMS off the best rigid motion) AnARAP ` +
      `${fixed(v('5.anarap.reshape_below'), 4)} / AnDefGrad ${fixed(v('5.andefgrad.reshape_below'), 4)} of the ` +
      `height, mean dihedral change ${fixed(v('5.anarap.bend_below'), 2)}° / ${fixed(v('5.andefgrad.bend_below'), 2)}°` +
      (v('5.andefgrad.reshape_below') < v('5.anarap.reshape_below') && v('5.andefgrad.bend_below') < v('5.anarap.bend_below')
        ? ' (AnDefGrad more local, as the paper says)'
        : ' (by these measures AnDefGrad is **not** more local than AnARAP here)') +
      `; mean edge strain there ${fixed(v('5.anarap.strain_below'), 4)} / ${fixed(v('5.andefgrad.strain_below'), 4)} ` +
      '(ARAP bends by turning its fans, which stretches no edge).',
    view: SPOOL,
    pictures: [
      { mesh: '5-rest', caption: 'rest, selection' },
      { mesh: '5-anarap', caption: 'AnARAP, rotate 30° about z' },
      { mesh: '5-andefgrad', caption: 'AnDefGrad, rotate 30° about z' },
    ],
  },
  {
    id: '6',
    title: 'Twist of the spool: the angle grows with height',
    test: 'tests/test_figures_post.cpp, "fig. 6: ..." (two scenes)',
    scene: 'closed/spool.off; a twist about x at k = 60°/unit: the whole spool, and the part above x = 0.1 with a ' +
      '0.35 geodesic falloff (origin on the axis at x = 0.1). The blue line is one meridian of the rest spool, carried along by the twist.',
    claim: 'Fig. 6: "The selected (orange) vertices of the post are twisted using anisotropic deformation gradients ' +
      'along a global direction. The twist angle increases with height."',
    measured: (v) => `rate fitted over the rings, for k = ${fixed(v('6.rate'), 0)}°/unit: whole spool ` +
      `AnDefGrad ${fixed(v('6.andefgrad.whole_rate'), 1)} (${pct(v('6.andefgrad.whole_rate'), v('6.rate'))}, worst ring ` +
      `${fixed(v('6.andefgrad.whole_worst_ring'), 2)}° off the line), AnARAP ${fixed(v('6.anarap.whole_rate'), 1)} ` +
      `(${pct(v('6.anarap.whole_rate'), v('6.rate'))}, ${fixed(v('6.anarap.whole_worst_ring'), 2)}°); with the ` +
      `falloff, on the fully selected rings: AnDefGrad ${fixed(v('6.andefgrad.falloff_rate'), 1)}, AnARAP ` +
      `${fixed(v('6.anarap.falloff_rate'), 1)}; unselected rings turn at most ` +
      `${fixed(v('6.andefgrad.falloff_unselected_turn'), 2)}° / ${fixed(v('6.anarap.falloff_unselected_turn'), 2)}°.`,
    view: SPOOL,
    pictures: [
      { mesh: '6-rest', caption: 'rest' },
      { mesh: '6-andefgrad-whole', caption: 'AnDefGrad, whole spool' },
      { mesh: '6-andefgrad-falloff', caption: 'AnDefGrad, top with falloff' },
      { mesh: '6-anarap-falloff', caption: 'AnARAP, top with falloff' },
    ],
  },
  {
    id: '7',
    title: 'Local stretch and local rotation about two axes',
    test: 'tests/test_figures_post.cpp, "fig. 7: ..." (two scenes)',
    scene: 'closed/spool.off; the upper half: su 1.4 along y; and every element turned 30° about z, then about y.',
    claim: 'Fig. 7: "Top: a stretch transformation performs anisotropic scaling along the desired direction. ' +
      'Bottom: a local rotation of the surface elements is performed for two different rotation axes. The blue ' +
      'regions remain unaffected and, therefore, act as deformation constraints." Text: "The deformation is shown ' +
      'to follow the desired direction while the features are preserved."',
    measured: (v) => `stretch (AnDefGrad / AnARAP): the top rim ×${fixed(v('7.andefgrad.stretch_along'), 3)} / ` +
      `×${fixed(v('7.anarap.stretch_along'), 3)} along y, ×${fixed(v('7.andefgrad.stretch_across'), 3)} / ` +
      `×${fixed(v('7.anarap.stretch_across'), 3)} across; the base rim ×${fixed(v('7.andefgrad.stretch_base'), 3)} / ` +
      `×${fixed(v('7.anarap.stretch_base'), 3)} along y; the selected rims' dihedral angles change ` +
      `${fixed(v('7.andefgrad.stretch_rim_change'), 2)}° / ${fixed(v('7.anarap.stretch_rim_change'), 2)}°. ` +
      `Rotation by 30° (AnDefGrad / AnARAP): the top rim's normal tilts ${fixed(v('7.andefgrad.rotate_z_tilt'), 1)}° / ` +
      `${fixed(v('7.anarap.rotate_z_tilt'), 1)}° about z and ${fixed(v('7.andefgrad.rotate_y_tilt'), 1)}° / ` +
      `${fixed(v('7.anarap.rotate_y_tilt'), 1)}° about y, at most ` +
      `${fixed(Math.max(v('7.andefgrad.rotate_z_off'), v('7.anarap.rotate_z_off'), v('7.andefgrad.rotate_y_off'),
        v('7.anarap.rotate_y_off')), 3)}° about the other axis.`,
    view: SPOOL,
    pictures: [
      { mesh: '7-rest', caption: 'rest, selection' },
      { mesh: '7-andefgrad-stretch', caption: 'AnDefGrad, su 1.4 along y' },
      { mesh: '7-andefgrad-rotate-z', caption: 'AnDefGrad, rotate 30° about z' },
      { mesh: '7-andefgrad-rotate-y', caption: 'AnDefGrad, rotate 30° about y' },
    ],
  },
  {
    id: '8',
    title: 'Knot tube along its curvature field: longer, or thicker',
    test: 'tests/test_paper_figures.cpp, "fig. 8: ..."',
    scene: 'closed/knot1.off (the MANIFEST\'s stand-in for the snake); direction: minimum curvature (along the ' +
      'tube); su 1.3 (parallel) or sv 1.3 (perpendicular) everywhere.',
    claim: 'Fig. 8: "Top: the snake is scaled parallel to the field to elongate it—its thickness is well preserved. ' +
      'Bottom: deformation is performed perpendicular to the field to achieve a thickening—its length is well ' +
      'preserved."',
    measured: (v) => `mean edge length ratio along / across the field: parallel ` +
      `×${fixed(v('8.andefgrad.parallel_along'), 3)} / ×${fixed(v('8.andefgrad.parallel_across'), 3)}, perpendicular ` +
      `×${fixed(v('8.andefgrad.perpendicular_along'), 3)} / ×${fixed(v('8.andefgrad.perpendicular_across'), 3)} ` +
      `(AnDefGrad); AnARAP ×${fixed(v('8.anarap.parallel_along'), 3)} / ×${fixed(v('8.anarap.parallel_across'), 3)} ` +
      `and ×${fixed(v('8.anarap.perpendicular_along'), 3)} / ×${fixed(v('8.anarap.perpendicular_across'), 3)}.`,
    view: { direction: [0.3, 0.4, 1], up: [0, 1, 0], frame: 'all' },
    pictures: [
      { mesh: '8-rest', caption: 'rest' },
      { mesh: '8-andefgrad-parallel', caption: 'AnDefGrad, su 1.3 along the field' },
      { mesh: '8-andefgrad-perpendicular', caption: 'AnDefGrad, sv 1.3 across it' },
    ],
  },
  {
    id: '9',
    title: 'Elongated chess piece: cage vs ARAP vs AnARAP vs AnDefGrad',
    test: 'tests/test_figures_post.cpp, "fig. 9: ..."',
    scene: 'closed/spool.off (stand-in for the chess piece); su 1.5 along x everywhere (linear map, AnARAP, ' +
      'AnDefGrad); ARAP: the top 5 % moved by half the height, the bottom 5 % held.',
    claim: 'Fig. 9: "Note that feature sharpness is lost using an isotropic energy formulation. Overall, ARAP—with ' +
      'or without anisotropy—does not perform as well at sharp edges as the anisotropic deformation gradient ' +
      'modeling (AnDefGrad)."',
    measured: (v) => `mean change of the rims' dihedral angles (rest above 40°): linear ` +
      `${fixed(v('9.linear.rim_change'), 1)}°, ARAP ${fixed(v('9.arap.rim_change'), 1)}°, AnARAP ` +
      `${fixed(v('9.anarap.rim_change'), 1)}°, AnDefGrad ${fixed(v('9.andefgrad.rim_change'), 1)}°; height ` +
      `×${fixed(v('9.linear.height_ratio'), 2)} / ×${fixed(v('9.arap.height_ratio'), 2)} / ` +
      `×${fixed(v('9.anarap.height_ratio'), 2)} / ×${fixed(v('9.andefgrad.height_ratio'), 2)} (same order); the core ` +
      `between the flanges ×${fixed(v('9.anarap.core_ratio'), 3)} (AnARAP) / ×${fixed(v('9.andefgrad.core_ratio'), 3)} ` +
      `(AnDefGrad) for su 1.5. Rims ` +
      `kept best first: ${['linear', 'arap', 'anarap', 'andefgrad']
        .sort((a, b) => v(`9.${a}.rim_change`) - v(`9.${b}.rim_change`)).map((m) => METHOD_NAMES[m]).join(', ')}.`,
    view: SPOOL,
    pictures: [
      { mesh: '9-rest', caption: 'rest' },
      { mesh: '9-linear', caption: 'linear (each vertex its own map)' },
      { mesh: '9-arap', caption: 'ARAP, by handles' },
      { mesh: '9-anarap', caption: 'AnARAP' },
      { mesh: '9-andefgrad', caption: 'AnDefGrad' },
    ],
  },
  {
    id: '10',
    title: 'A spatially varying field: the smile',
    test: 'tests/test_paper_figures.cpp, "fig. 10: ..."',
    scene: 'open/demosthenes-low-res.obj (stand-in for the Roman bust); a sphere of radius 0.15 around the head\'s ' +
      'frontmost point, AnARAP su 1.3 along the dense field (1, (x − xc)/r, 0), bent upwards away from the middle, ' +
      'and along the straight field (1, 0, 0). Heat map: the app\'s stretch (full colour at ×2). The beard is not ' +
      'built.',
    claim: 'Fig. 10: "Top: the vector field (left) is bent along the lips to cause the Roman bust (middle) to smile ' +
      '(right)."',
    measured: (v) => `the ends of the band rise ${fixed(v('10.anarap.bent_rise'), 3)} of the radius relative to its ` +
      `middle with the bent field, ${fixed(v('10.anarap.straight_rise'), 3)} with the straight one.`,
    view: { direction: [0, 0.1, 1], up: [0, 1, 0], frame: 'selection' },
    pictures: [
      { mesh: '10-rest', caption: 'rest, selection' },
      { mesh: '10-anarap-straight', caption: 'straight field, stretch' },
      { mesh: '10-anarap-bent', caption: 'bent field, stretch' },
    ],
  },
  {
    id: '11',
    title: 'Garment flattening with directed compression',
    test: 'tests/test_flatten.cpp, "flatten (fig. 11): ..."',
    scene: 'open/human_woman_torso_front_patch.obj; an under-bust band, su 0.8 along a sagging line given by four ' +
      'arrows (their vertices marked), ours (anisotropic) and the uniform baseline (flatten, then scale the ' +
      'pattern along one direction). Heat map: the compression error |achieved / wanted − 1| (full colour at 10 %).',
    claim: 'Fig. 11: "The desired compression directions are defined for a patch (left). The original method of ' +
      'scaling fails to distribute the compression well (middle). Our method maintains the desired compression ' +
      'over the whole surface."',
    measured: (v) => `compression error mean / max: ours ${fixed(v('11.ours.compression_error_mean'), 4)} / ` +
      `${fixed(v('11.ours.compression_error_max'), 3)}, baseline ${fixed(v('11.baseline.compression_error_mean'), 4)} / ` +
      `${fixed(v('11.baseline.compression_error_max'), 3)}; cross error mean ` +
      `${fixed(v('11.ours.cross_error_mean'), 4)} / ${fixed(v('11.baseline.cross_error_mean'), 4)}; ` +
      `${v('11.ours.flipped')} / ${v('11.baseline.flipped')} folded triangles; ${v('11.ours.iterations')} / ` +
      `${v('11.baseline.iterations')} iterations.`,
    view: { direction: [0, 0, 1], up: [0, 1, 0], frame: 'own' },
    pictures: [
      { mesh: '11-rest', caption: 'the panel, arrow vertices marked' },
      { mesh: '11-baseline-3d', caption: 'baseline: error on the panel' },
      { mesh: '11-ours-3d', caption: 'ours: error on the panel' },
      { mesh: '11-baseline-pattern', caption: 'baseline pattern' },
      { mesh: '11-ours-pattern', caption: 'ours: pattern' },
    ],
  },
];
