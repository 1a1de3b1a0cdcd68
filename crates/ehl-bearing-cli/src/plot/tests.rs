//! Tests of the plotting layer.

use super::*;

fn test_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ehl-plot-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Width and height from a PNG header, after checking its signature.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert!(bytes.len() > 33, "{} is too short", path.display());
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    (w, h)
}

fn check_outputs(stem: &Path, title: &str, size: (u32, u32)) -> String {
    assert_eq!(png_size(&with_ext(stem, "png")), size);
    let svg = std::fs::read_to_string(with_ext(stem, "svg")).unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains(title), "title missing from the SVG");
    svg
}

fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect()
}

/// A heat map titled `title` of `z` on `(x, y)`, with the axes labelled x, y and z.
fn xyz<'a>(title: &'a str, x: &'a [f64], y: &'a [f64], z: &'a [Vec<f64>]) -> HeatmapData<'a> {
    HeatmapData {
        title,
        x_label: "x",
        y_label: "y",
        x,
        y,
        z,
        z_label: "z",
    }
}

/// An EHL-like pressure map: Hertz dome plus an outlet spike, zero outside.
fn pressure_map(n: usize) -> (Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
    let x = linspace(-4.5, 1.5, n);
    let y = linspace(-3.0, 3.0, n);
    let z = y
        .iter()
        .map(|&yy| {
            x.iter()
                .map(|&xx| {
                    let r2 = xx * xx + yy * yy;
                    let dome = (1.0 - r2).max(0.0).sqrt();
                    let spike =
                        0.6 * (-((xx - 0.85) / 0.04).powi(2)).exp() * (1.0 - yy * yy).max(0.0);
                    dome + spike
                })
                .collect()
        })
        .collect();
    (x, y, z)
}

#[test]
fn line_chart_writes_svg_and_png() {
    let stem = test_dir("line").join("q_delta");
    let x = linspace(0.0, 10.0, 30);
    let y: Vec<f64> = x.iter().map(|d| 3.0 * d.powf(1.5)).collect();
    let series = [
        Series::markers("computed", x.clone(), y.clone()),
        Series::line("fit Q = K δ^1.5", x, y),
    ];
    line_chart(&stem, "Load against approach", "δ (µm)", "Q (N)", &series).unwrap();
    check_outputs(
        &stem,
        "Load against approach",
        (FIGURE_WIDTH, FIGURE_HEIGHT),
    );
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn log_axes_and_explicit_ranges() {
    let stem = test_dir("log").join("k");
    let w = linspace(10.0, 1000.0, 20);
    let series: Vec<Series> = [1.0, 2.0, 4.0]
        .iter()
        .map(|u| {
            let k = w.iter().map(|w| 1e8 * u * w.powf(1.0 / 3.0)).collect();
            Series::new(
                format!("u = {u} m/s"),
                w.clone(),
                k,
                SeriesStyle::LineAndMarkers,
            )
        })
        .collect();
    let opts = ChartOptions {
        x_log: true,
        y_log: true,
        ..Default::default()
    };
    line_chart_with(&stem, "Stiffness", "Q (N)", "K (N/m)", &series, &opts).unwrap();
    check_outputs(&stem, "Stiffness", (FIGURE_WIDTH, FIGURE_HEIGHT));

    let opts = ChartOptions {
        x_range: Some((0.0, 500.0)),
        y_range: Some((0.0, 2e9)),
        ..Default::default()
    };
    line_chart_with(&stem, "Ranged", "Q (N)", "K (N/m)", &series, &opts).unwrap();
    check_outputs(&stem, "Ranged", (FIGURE_WIDTH, FIGURE_HEIGHT));

    // Non-positive data on a log axis is skipped, not an error.
    let s = [Series::line(
        "a",
        vec![-1.0, 0.0, 1.0, 10.0],
        vec![1.0, 2.0, 3.0, 4.0],
    )];
    let opts = ChartOptions {
        x_log: true,
        ..Default::default()
    };
    line_chart_with(&stem, "Skip", "x", "y", &s, &opts).unwrap();
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn stacked_charts_write_svg_and_png() {
    let stem = test_dir("stacked").join("dq");
    let t = linspace(0.0, 1e-3, 200);
    let d: Vec<f64> = t.iter().map(|t| 1.0 + 0.2 * (2e4 * t).sin()).collect();
    let q: Vec<f64> = d.iter().map(|d| 500.0 * d.powf(1.5)).collect();
    let panels = vec![
        ("δ (µm)".to_string(), vec![Series::line("δ", t.clone(), d)]),
        ("Q (N)".to_string(), vec![Series::line("Q", t, q)]),
    ];
    stacked_charts(&stem, "Approach and load", "t (s)", &panels).unwrap();
    check_outputs(
        &stem,
        "Approach and load",
        (FIGURE_WIDTH, stacked_height(2)),
    );
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn dual_axis_chart_writes_svg_and_png() {
    let stem = test_dir("dual").join("profile");
    let x = linspace(-4.5, 1.5, 200);
    let p: Vec<f64> = x.iter().map(|x| (1.0 - x * x).max(0.0).sqrt()).collect();
    let h: Vec<f64> = x.iter().map(|x| 0.3 + 0.2 * x * x).collect();
    let left = [Series::line("P", x.clone(), p)];
    let right = [Series::line("h", x, h)];
    dual_axis_chart(&stem, "Profiles", "X", ("P", &left), ("h (µm)", &right)).unwrap();
    check_outputs(&stem, "Profiles", (FIGURE_WIDTH, FIGURE_HEIGHT));
    // One side empty is fine; both empty or uneven is an error.
    dual_axis_chart(&stem, "Left only", "X", ("P", &left), ("h", &[])).unwrap();
    assert!(dual_axis_chart(&stem, "t", "X", ("P", &[]), ("h", &[])).is_err());
    let uneven = [Series::line("u", vec![1.0, 2.0], vec![1.0])];
    assert!(dual_axis_chart(&stem, "t", "X", ("P", &left), ("h", &uneven)).is_err());
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn heatmap_writes_svg_and_png() {
    let stem = test_dir("heat").join("p");
    let (x, y, z) = pressure_map(65);
    let map = HeatmapData {
        title: "Pressure",
        x_label: "X = x/a",
        y_label: "Y = y/b",
        x: &x,
        y: &y,
        z: &z,
        z_label: "P = p/p_H",
    };
    heatmap(&stem, &map).unwrap();
    let svg = check_outputs(&stem, "Pressure", (FIGURE_WIDTH, FIGURE_HEIGHT));
    assert!(svg.contains("data:image/png;base64,"), "map not embedded");
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn large_heatmap_with_contour_and_overlay() {
    let stem = test_dir("heat513").join("p");
    let (x, y, z) = pressure_map(513);
    let t = linspace(0.0, std::f64::consts::TAU, 100);
    let opts = HeatmapOptions {
        contour_levels: vec![0.05],
        overlays: vec![Series::line(
            "Hertz ellipse",
            t.iter().map(|t| t.cos()).collect(),
            t.iter().map(|t| t.sin()).collect(),
        )],
        ..Default::default()
    };
    let map = HeatmapData {
        title: "Pressure 513",
        x_label: "X",
        y_label: "Y",
        x: &x,
        y: &y,
        z: &z,
        z_label: "P",
    };
    heatmap_with(&stem, &map, &opts).unwrap();
    let svg = check_outputs(&stem, "Pressure 513", (FIGURE_WIDTH, FIGURE_HEIGHT));
    assert!(svg.len() < 4_000_000, "SVG is {} bytes", svg.len());
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn nan_and_inf_do_not_panic() {
    let dir = test_dir("nan");
    let x = vec![0.0, 1.0, 2.0, f64::NAN, 4.0, 5.0, 6.0];
    let y = vec![1.0, f64::INFINITY, 3.0, 4.0, f64::NAN, 2.0, 1.0];
    let s = [
        Series::new("a", x.clone(), y.clone(), SeriesStyle::LineAndMarkers),
        Series::markers("b", y, x),
        Series::line("empty", vec![], vec![]),
    ];
    line_chart(&dir.join("line"), "NaN line", "x", "y", &s).unwrap();
    let panels = vec![
        ("a".to_string(), s.to_vec()),
        (
            "all NaN".to_string(),
            vec![Series::line("n", vec![f64::NAN], vec![1.0])],
        ),
    ];
    stacked_charts(&dir.join("stacked"), "NaN stacked", "x", &panels).unwrap();

    let (gx, gy, mut z) = pressure_map(33);
    z[3][4] = f64::NAN;
    z[10][10] = f64::INFINITY;
    z[20][5] = f64::NEG_INFINITY;
    heatmap(&dir.join("heat"), &xyz("NaN heat", &gx, &gy, &z)).unwrap();
    // A constant field still gets a usable colour scale.
    let flat = vec![vec![2.0; gx.len()]; gy.len()];
    heatmap(&dir.join("flat"), &xyz("Flat", &gx, &gy, &flat)).unwrap();
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_input_is_an_error() {
    let stem = test_dir("bad").join("x");
    let ok = Series::line("ok", vec![0.0, 1.0], vec![0.0, 1.0]);
    let uneven = Series::line("uneven", vec![0.0, 1.0, 2.0], vec![0.0, 1.0]);
    assert!(line_chart(&stem, "t", "x", "y", &[]).is_err());
    assert!(line_chart(&stem, "t", "x", "y", &[ok.clone(), uneven.clone()]).is_err());
    let nan = Series::line("nan", vec![f64::NAN], vec![f64::NAN]);
    assert!(line_chart(&stem, "t", "x", "y", &[nan]).is_err());
    let empty = Series::line("empty", vec![], vec![]);
    assert!(line_chart(&stem, "t", "x", "y", &[empty]).is_err());
    let bad_range = ChartOptions {
        y_range: Some((1.0, 0.0)),
        ..Default::default()
    };
    assert!(line_chart_with(&stem, "t", "x", "y", std::slice::from_ref(&ok), &bad_range).is_err());
    let bad_log = ChartOptions {
        x_log: true,
        x_range: Some((-1.0, 10.0)),
        ..Default::default()
    };
    assert!(line_chart_with(&stem, "t", "x", "y", std::slice::from_ref(&ok), &bad_log).is_err());
    assert!(stacked_charts(&stem, "t", "x", &[]).is_err());
    assert!(stacked_charts(&stem, "t", "x", &[("y".into(), vec![uneven])]).is_err());

    let x = [0.0, 1.0, 2.0];
    let y = [0.0, 1.0];
    let z = vec![vec![0.0; 3]; 2];
    assert!(heatmap(&stem, &xyz("t", &x, &y, &z)).is_ok());
    let ragged = vec![vec![0.0; 3], vec![0.0; 2]];
    assert!(heatmap(&stem, &xyz("t", &x, &y, &ragged)).is_err());
    assert!(heatmap(&stem, &xyz("t", &x, &y, &z[..1])).is_err());
    assert!(heatmap(&stem, &xyz("t", &[2.0, 1.0, 0.0], &y, &z)).is_err());
    assert!(heatmap(&stem, &xyz("t", &[0.0], &[0.0], &[vec![1.0]])).is_err());
    let all_nan = vec![vec![f64::NAN; 3]; 2];
    assert!(heatmap(&stem, &xyz("t", &x, &y, &all_nan)).is_err());
    let _ = std::fs::remove_dir_all(stem.parent().unwrap());
}

#[test]
fn extreme_ranges_do_not_hang_or_panic() {
    let dir = test_dir("extreme");
    let cases = [
        (vec![0.0, 1.0], vec![1e300, 1e300 * (1.0 + 1e-15)]),
        (vec![0.0, 1.0], vec![1e-300, 2e-300]),
        (vec![0.0, 1.0], vec![5.0, 5.0]),
        (vec![0.0, 1.0], vec![0.0, 0.0]),
        (vec![1e-9, 2e-9], vec![-1e-12, 1e-12]),
    ];
    for (k, (x, y)) in cases.into_iter().enumerate() {
        let s = [Series::line("s", x, y)];
        line_chart(&dir.join(format!("c{k}")), "extreme", "x", "y", &s).unwrap();
    }
    let s = [Series::line("s", vec![0.0, 1.0], vec![-1e308, 1e308])];
    assert!(line_chart(&dir.join("overflow"), "extreme", "x", "y", &s).is_err());
    let log = ChartOptions {
        y_log: true,
        ..Default::default()
    };
    let s = [Series::line(
        "s",
        vec![0.0, 1.0, 2.0],
        vec![1e-300, 1.0, 1e300],
    )];
    line_chart_with(&dir.join("log"), "extreme", "x", "y", &s, &log).unwrap();
    let wide = ChartOptions {
        y_log: true,
        y_range: Some((1e-100, 1e100)),
        ..Default::default()
    };
    assert!(line_chart_with(&dir.join("log"), "extreme", "x", "y", &s, &wide).is_err());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn tick_labels_are_short() {
    let lin = Axis::new(-1.0, 2.0, false);
    assert_eq!(lin.tick_label(0.30000000000000004), "0.3");
    assert_eq!(lin.tick_label(5.551115123125783e-17), "0");
    assert_eq!(lin.tick_label(-2.0), "-2");
    assert_eq!(lin.tick_label(f64::NAN), "");
    let time = Axis::new(0.0, 2e-3, false);
    assert_eq!(time.tick_label(5e-4), "0.0005");
    assert_eq!(time.tick_label(1.5e-3), "0.0015");
    let film = Axis::new(0.0, 1e-6, false);
    assert_eq!(film.tick_label(1.5e-7), "1.5e-7");
    assert_eq!(film.tick_label(0.0), "0");
    let stiff = Axis::new(5e8, 3e9, false);
    assert_eq!(stiff.tick_label(2e9), "2e9");
    assert_eq!(stiff.tick_label(2.5e9), "2.5e9");
    let log = Axis::new(50.0, 3000.0, true);
    assert_eq!(log.tick_label(200.0), "200");
    assert_eq!(log.tick_label(1000.0), "1000");
    assert_eq!(log.tick_label(700.0), "700");
    assert_eq!(log.tick_label(750.0), "");
    assert_eq!(Axis::new(1e-8, 1e-5, true).tick_label(2e-7), "2e-7");
}

#[test]
fn log_ticks_label_the_decade_the_data_start_in() {
    // Contact loads from 27 N to 1100 N (the seed study, 15 % margins): labelled from 30 N on,
    // where plotters' own ticks start at 100 N.
    let q = Axis::new(27.0 / 1.15, 1100.0 * 1.15, true);
    let (labelled, grid) = q.log_ticks(X_LABELS);
    assert_eq!(
        labelled,
        vec![30.0, 50.0, 100.0, 200.0, 300.0, 500.0, 1000.0]
    );
    for v in [40.0, 60.0, 400.0, 900.0] {
        assert!(grid.contains(&v), "{v} not in {grid:?}");
    }
    assert!(labelled.iter().all(|v| !grid.contains(v)));
    assert!(labelled.iter().all(|v| !q.tick_label(*v).is_empty()));
    assert_eq!(
        Axis::new(18.0, 1265.0, true).log_ticks(X_LABELS).0,
        vec![20.0, 30.0, 50.0, 100.0, 200.0, 300.0, 500.0, 1000.0]
    );
    // Three decades: 1, 2 and 5 times the powers of ten (1-2-3-5 would be 12 labels).
    assert_eq!(
        Axis::new(1.5, 1100.0, true).log_ticks(X_LABELS).0,
        vec![2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0]
    );
    // A narrow range: the integer multiples of the decade.
    assert_eq!(
        Axis::new(27.0, 45.0, true).log_ticks(X_LABELS).0,
        vec![30.0, 40.0]
    );
    // Too many 1-2-5 ticks: powers of ten, every other one when still too many.
    let (wide, _) = Axis::new(1e-12, 1e3, true).log_ticks(Y_LABELS);
    assert_eq!(wide.len(), 8, "{wide:?}");
    assert!(wide
        .iter()
        .all(|v| (v.log10() - v.log10().round()).abs() < 1e-9));
    assert_eq!(wide[0], 1e-12);
    assert_eq!(Axis::new(1e-7, 1e-5, true).log_ticks(Y_LABELS).0[1], 2e-7);
}

#[test]
fn shared_legend_room_keeps_a_six_row_legend_off_the_data() {
    // Markers in every corner of a fixed y range (the study figures' shared scale), six legend
    // rows: without room every corner of the plot is covered, with it none is.
    let x = linspace(25.0, 1200.0, 40);
    let series: Vec<Series> = (0..6)
        .map(|k| {
            let y = x
                .iter()
                .map(|q| 10.0 + 8.0 * k as f64 + 2.0 * q.ln())
                .collect();
            Series::markers(
                format!("trend ΔF(Q, {k}000 rpm) with a long label"),
                x.clone(),
                y,
            )
        })
        .collect();
    let y_axis = Axis::fit(series.iter().flat_map(|s| s.y.clone()), false, None)
        .unwrap()
        .unwrap();
    let x_axis = Axis::new(20.0, 1300.0, true);
    let mut buf = vec![0u8; 1000 * 560 * 3];
    let area = BitMapBackend::with_buffer(&mut buf, (1000, 560)).into_drawing_area();
    let panel = |y: Axis| Panel {
        x_label: "Q (N)",
        y_label: "ΔF (N)",
        show_x: true,
        x: x_axis,
        y,
        series: &series,
        y_area: 90,
        margin_bottom: MARGIN,
        y_fixed: true,
    };
    let room = legend_room(&area, &panel(y_axis)).expect("every corner has data");
    assert!(room > 0.1 && room < 0.7, "{room}");
    let raised = y_axis.with_top_room(room);
    assert_eq!(raised.lo, y_axis.lo);
    assert!(legend_room(&area, &panel(raised)).is_none());
}

#[test]
fn contour_of_a_cone_is_a_circle() {
    let x = linspace(-2.0, 2.0, 81);
    let y = x.clone();
    let z: Vec<Vec<f64>> = y
        .iter()
        .map(|b| x.iter().map(|a| (a * a + b * b).sqrt()).collect())
        .collect();
    let g = Grid {
        x: &x,
        y: &y,
        z: &z,
    };
    let segs = g.contour(1.0);
    assert!(segs.len() > 50);
    for p in segs.iter().flatten() {
        let r = (p.0 * p.0 + p.1 * p.1).sqrt();
        assert!((r - 1.0).abs() < 0.01, "r = {r}");
    }
}

/// Renders one example of each kind to /tmp/plot-demo for a visual check:
/// `cargo test -p ehl-bearing-cli plot::tests::demo -- --ignored`.
#[test]
#[ignore]
fn demo() {
    let dir = Path::new("/tmp/plot-demo");
    std::fs::create_dir_all(dir).unwrap();

    let d = linspace(0.0, 12.0, 13);
    let q: Vec<f64> = d
        .iter()
        .enumerate()
        .map(|(k, d)| 21.5 * d.powf(1.5) * (1.0 + 0.03 * ((k * 7 % 5) as f64 - 2.0) / 2.0))
        .collect();
    let df = linspace(0.0, 12.0, 100);
    let fit: Vec<f64> = df.iter().map(|d| 21.5 * d.powf(1.5)).collect();
    line_chart(
        &dir.join("q_delta"),
        "Contact load against mutual approach",
        "δ (µm)",
        "Q (N)",
        &[
            Series::markers("EHL solution", d, q),
            Series::line("fit Q = 21.5 δ^1.5", df, fit),
        ],
    )
    .unwrap();

    let load = linspace(50.0, 2000.0, 12);
    let speeds = [0.5, 2.0, 8.0];
    let k: Vec<Series> = speeds
        .iter()
        .map(|u| {
            let v = load
                .iter()
                .map(|q| 2.1e8 * q.powf(1.0 / 3.0) * (1.0 - 0.02 * u))
                .collect();
            Series::new(
                format!("u = {u} m/s"),
                load.clone(),
                v,
                SeriesStyle::LineAndMarkers,
            )
        })
        .collect();
    line_chart(
        &dir.join("stiffness"),
        "Contact stiffness",
        "Q (N)",
        "K (N/m)",
        &k,
    )
    .unwrap();
    let lift: Vec<Series> = speeds
        .iter()
        .map(|u| {
            let v = load.iter().map(|q| 0.05 * u * q.powf(0.6)).collect();
            Series::new(
                format!("u = {u} m/s"),
                load.clone(),
                v,
                SeriesStyle::LineAndMarkers,
            )
        })
        .collect();
    line_chart_with(
        &dir.join("lift_log"),
        "Lift force (log–log)",
        "Q (N)",
        "ΔF (N)",
        &lift,
        &ChartOptions {
            x_log: true,
            y_log: true,
            ..Default::default()
        },
    )
    .unwrap();

    let t = linspace(0.0, 2e-3, 400);
    let delta: Vec<f64> = t.iter().map(|t| 8.0 + 2.0 * (6283.0 * t).sin()).collect();
    let qq: Vec<f64> = delta.iter().map(|d| 21.5 * d.powf(1.5)).collect();
    let qs: Vec<f64> = delta.iter().map(|d| 21.5 * (d - 0.3).powf(1.5)).collect();
    stacked_charts(
        &dir.join("stacked"),
        "Approach and load in time",
        "t (s)",
        &[
            (
                "δ (µm)".to_string(),
                vec![Series::line("δ", t.clone(), delta)],
            ),
            (
                "Q (N)".to_string(),
                vec![
                    Series::line("EHL", t.clone(), qq),
                    Series::line("Hertz", t, qs),
                ],
            ),
        ],
    )
    .unwrap();

    let (x, y, z) = pressure_map(257);
    let th = linspace(0.0, std::f64::consts::TAU, 120);
    heatmap_with(
        &dir.join("pressure_map"),
        &HeatmapData {
            title: "EHL pressure",
            x_label: "X = x/a",
            y_label: "Y = y/b",
            x: &x,
            y: &y,
            z: &z,
            z_label: "P = p/p_H",
        },
        &HeatmapOptions {
            contour_levels: vec![0.5],
            overlays: vec![Series::line(
                "Hertz contact",
                th.iter().map(|t| t.cos()).collect(),
                th.iter().map(|t| t.sin()).collect(),
            )],
            ..Default::default()
        },
    )
    .unwrap();
    let film: Vec<Vec<f64>> = y
        .iter()
        .map(|&b| {
            x.iter()
                .map(|&a| {
                    let r2 = a * a + b * b;
                    if r2 < 1.0 {
                        0.35e-6 - 0.1e-6 * (-((a - 0.8) / 0.1).powi(2)).exp() + 0.05e-6 * b * b
                    } else {
                        0.35e-6 + 0.5e-6 * (r2 - 1.0)
                    }
                })
                .collect()
        })
        .collect();
    heatmap_with(
        &dir.join("film_map"),
        &HeatmapData {
            title: "EHL film thickness",
            x_label: "x (mm)",
            y_label: "y (mm)",
            x: &x.iter().map(|v| v * 0.2).collect::<Vec<_>>(),
            y: &y.iter().map(|v| v * 0.2).collect::<Vec<_>>(),
            z: &film,
            z_label: "h (m)",
        },
        &HeatmapOptions {
            z_range: Some((0.0, 1.0e-6)),
            ..Default::default()
        },
    )
    .unwrap();
    let mid = y.len() / 2;
    dual_axis_chart(
        &dir.join("centre_line_dual"),
        "Centre-line pressure and film",
        "X = x/a",
        (
            "P = p/p_H",
            &[Series::line("pressure", x.clone(), z[mid].clone())],
        ),
        (
            "h (µm)",
            &[Series::line(
                "film",
                x.clone(),
                film[mid].iter().map(|h| h * 1e6).collect(),
            )],
        ),
    )
    .unwrap();
    stacked_charts(
        &dir.join("centre_line"),
        "Centre-line profiles",
        "X = x/a",
        &[
            (
                "P = p/p_H".to_string(),
                vec![Series::line("P", x.clone(), z[mid].clone())],
            ),
            (
                "h (µm)".to_string(),
                vec![Series::line(
                    "h",
                    x.clone(),
                    film[mid].iter().map(|h| h * 1e6).collect(),
                )],
            ),
        ],
    )
    .unwrap();
}

#[test]
fn titles_wrap_within_the_width_and_keep_equations_together() {
    let title = "Contact law, quasi-static method — w0 = 600.0 N, u_s = 10.85 m/s, a = 1.390 mm, \
                 b = 0.103 mm, p_h = 2.01 GPa (M = 2362, L = 25.3)";
    let lines = wrap_title(title, 26.0, 970.0);
    assert!(lines.len() >= 2, "{lines:?}");
    for l in &lines {
        assert!(text_box(l, 26.0).0 <= 970.0, "too wide: {l}");
        assert!(
            !l.ends_with('=') && !l.starts_with('='),
            "split at '=': {lines:?}"
        );
    }
    assert_eq!(wrap_title("short", 26.0, 970.0), vec!["short".to_string()]);
}
