//! report.html's fitness plot: its legend sits above the plot area, never on
//! a curve; its table gives every cell of a column the same decimals (issue
//! 25). The page's plotting script runs under Node.js when it is installed
//! (skipped otherwise); the colours are checked by `report_html`'s unit tests.

use std::process::Command;

use crate::common::*;

const PLOTS_JS: &str = include_str!("../../assets/plots.js");

/// Runs `script` after plots.js under Node.js; `None` without Node.js.
fn node(script: &str) -> Option<String> {
    let program = format!("{PLOTS_JS}\n{script}");
    let out = match Command::new("node").arg("-e").arg(&program).output() {
        Ok(out) => out,
        Err(_) => {
            skipped("Node.js (node) is not installed");
            return None;
        }
    };
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(String::from_utf8(out.stdout).unwrap())
}

/// The numbers of `attr='…'` in every element of `svg` with class `class`.
fn attrs(svg: &str, class: &str, attr: &str) -> Vec<f64> {
    svg.split('<')
        .filter(|e| e.contains(&format!("class='{class}'")))
        .map(|e| {
            let start = e.find(&format!(" {attr}='")).unwrap() + attr.len() + 3;
            e[start..start + e[start..].find('\'').unwrap()]
                .parse()
                .unwrap()
        })
        .collect()
}

#[test]
fn legend_is_above_the_plot_area() {
    let Some(svg) = node(
        "console.log(VivaePlots.lines([1, 2, 3], [\
           { name: 'best', color: '#45347e', values: [1, 4, 5] },\
           { name: 'mean', color: '#e66101', values: [0.5, 2, 3] }],\
         'generation', 'fitness'));",
    ) else {
        return;
    };
    // The plot area is the first rect; its top edge is y.
    let area = svg.split("<rect").nth(1).unwrap();
    let top: f64 = area
        .split("y='")
        .nth(1)
        .unwrap()
        .split('\'')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let ys = attrs(&svg, "legend", "y");
    assert_eq!(ys.len(), 4, "{svg}");
    for y in ys {
        assert!(
            y < top,
            "legend at y {y} inside the plot area (top {top}): {svg}"
        );
    }
}

#[test]
fn table_columns_have_one_number_format_each() {
    let Some(html) = node(
        "var row = function (g, best, nodes) { return { generation: g, best: best, mean: 1, median: 1.5,\
           worst: 0, species: 2, cppn_nodes: nodes, cppn_links: 12.345, substrate_links: 40 }; };\
         console.log(VivaePlots.table([row(1, 8, 8), row(2, 8.06, 8.06)]));",
    ) else {
        return;
    };
    let cells: Vec<&str> = html
        .split("<td>")
        .skip(1)
        .map(|c| c.split("</td>").next().unwrap())
        .collect();
    assert_eq!(
        cells,
        [
            "1", "8.0000", "1.0000", "1.5000", "0.0000", "2", "8.00", "12.35", "40", //
            "2", "8.0600", "1.0000", "1.5000", "0.0000", "2", "8.06", "12.35", "40",
        ],
        "{html}"
    );
}
