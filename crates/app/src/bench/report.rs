//! The benchmark report: one markdown page rebuilt from the CSV files a
//! `helixhair bench` run has just written, so that a rerun replaces it
//! and no figure in it is typed by hand.
//!
//! # What the page holds
//!
//! ```text
//! # Benchmarks                                  <- title
//! AMD EPYC, 2 threads, x86_64 (AVX2, FMA) · 2026-11-28 · quick run …   <- the one header line
//! Rebuilt by `helixhair bench …`                <- the command that made it
//! ## cost: seconds per step against N …         <- one section per study run
//! ![cost.svg](results/cost.svg)                 <- its charts, linked
//! | method | elements | median_us | …           <- each CSV as a table
//! ```
//!
//! The machine and the date appear once, in the header line, because every
//! figure below was measured in that one run; a quick run (`--quick`) says
//! so in the same line, since its sizes are small and its figures are not
//! the published ones.
//!
//! # How it reads the run
//!
//! The run hands each study its output paths ([`super::BenchContext::file`])
//! and keeps them, study by study; the report shows exactly those: each
//! SVG as a chart and each CSV as a table, in the order the study wrote
//! them. A stale file left in the folder by an earlier run of another
//! study never appears under this run's header. Numbers are printed to four significant
//! digits ([`format_cell`]); long tables are cut at [`MAX_ROWS`] rows with
//! a link to the whole CSV. Links are relative to the report's folder
//! ([`relative_link`]), so `--out docs/results --report docs/benchmarks.md`
//! links `results/cost.svg`.
//!
//! The pure parts ([`csv_to_markdown`], [`render_report`],
//! [`relative_link`], [`civil_date`]) take and return strings; the unit
//! tests below check them against hand-written answers.

use std::fmt::Write as _;
use std::path::{Component, Path, PathBuf};
use std::time::SystemTime;

use anyhow::Context as _;

use super::Study;

/// Rows of a CSV shown in the report; the rest is linked.
pub const MAX_ROWS: usize = 40;

/// A study's section title: its name and its question.
pub fn title(study: Study) -> &'static str {
    match study {
        Study::Cost => "cost: microseconds per step against element count, one strand, one thread",
        Study::Accuracy => {
            "accuracy: error against cost on three scenes; CG iterations against Block-diagonal's error"
        }
        Study::Stability => {
            "stability: stable, damped-out or blown-up over time step, stiffness and head motion"
        }
        Study::Modes => "modes: first-mode frequency and damping against element count",
        Study::Throughput => {
            "throughput: element-steps per second of each engine against strand count"
        }
        Study::Volume => "volume: the hair–hair model on a full head settled 5 s",
        Study::VolumeShake => "volume-shake: interpenetration and energy during a head shake",
        Study::VolumeCost => "volume-cost: the hair–hair model's share of a frame",
        Study::Soak => "soak: a full head under random head motion, per engine",
        Study::Groom => {
            "groom: physics milliseconds per 60 Hz frame of a whole groom, and where it goes"
        }
    }
}

/// The one header line's parts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReportHeader {
    /// The machine, in words (CPU, threads, instruction sets).
    pub machine: String,
    /// The date of the run, `YYYY-MM-DD` (UTC).
    pub date: String,
    /// Whether the run was `--quick`.
    pub quick: bool,
    /// The command line that made the report.
    pub command: String,
}

/// One study's section, read from the files of the run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    /// The section title.
    pub title: String,
    /// Chart links (relative to the report), in order.
    pub charts: Vec<String>,
    /// Each table: its link and its CSV text.
    pub tables: Vec<(String, String)>,
}

/// Writes to `report_path` the report of the files each study of the run
/// wrote (`written`: each study with its files, in order).
pub fn write_report(
    report_path: &Path,
    written: &[(Study, Vec<PathBuf>)],
    header: &ReportHeader,
) -> anyhow::Result<()> {
    let report_dir = report_path.parent().unwrap_or(Path::new(""));
    let mut sections = Vec::new();
    for (study, files) in written {
        let mut section = Section {
            title: title(*study).to_owned(),
            charts: Vec::new(),
            tables: Vec::new(),
        };
        let has_extension = |path: &Path, ext: &str| path.extension().is_some_and(|e| e == ext);
        for path in files {
            if has_extension(path, "svg") {
                section.charts.push(relative_link(report_dir, path)?);
            } else if has_extension(path, "csv") {
                let text = std::fs::read_to_string(path)
                    .with_context(|| format!("cannot read {}", path.display()))?;
                section
                    .tables
                    .push((relative_link(report_dir, path)?, text));
            }
        }
        if !section.charts.is_empty() || !section.tables.is_empty() {
            sections.push(section);
        }
    }
    let text = render_report(header, &sections)?;
    if !report_dir.as_os_str().is_empty() {
        std::fs::create_dir_all(report_dir)
            .with_context(|| format!("cannot create {}", report_dir.display()))?;
    }
    crate::atomic_write::write_atomically(report_path, text.as_bytes())
        .with_context(|| format!("cannot write the report {}", report_path.display()))
}

/// The report's markdown.
pub fn render_report(header: &ReportHeader, sections: &[Section]) -> anyhow::Result<String> {
    let mut md = String::from("# Benchmarks\n\n");
    let kind = if header.quick {
        "quick run (small sizes: checks that every study runs, not the published figures)"
    } else {
        "full run"
    };
    writeln!(md, "{} · {} · {kind}\n", header.machine, header.date)?;
    writeln!(
        md,
        "Rebuilt by `{}`, which replaces this page and the files it links; \
         every figure below comes from that one run.\n",
        header.command
    )?;
    for section in sections {
        writeln!(md, "## {}\n", section.title)?;
        for chart in &section.charts {
            let name = chart.rsplit('/').next().unwrap_or(chart);
            writeln!(md, "![{name}]({chart})\n")?;
        }
        for (link, text) in &section.tables {
            let name = link.rsplit('/').next().unwrap_or(link);
            writeln!(md, "[`{name}`]({link}):\n")?;
            md.push_str(&csv_to_markdown(text, link, MAX_ROWS)?);
            md.push('\n');
        }
    }
    Ok(md)
}

/// A CSV text as a markdown table, numbers to four significant digits, at
/// most `max_rows` rows; a line after the table links the rest.
pub fn csv_to_markdown(text: &str, link: &str, max_rows: usize) -> anyhow::Result<String> {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .context("a CSV without a header row")?
        .iter()
        .map(str::to_owned)
        .collect();
    let mut md = format!("| {} |\n", header.join(" | "));
    md.push_str(&format!("|{}\n", " --- |".repeat(header.len())));
    let mut rows = 0;
    for record in reader.records() {
        let record = record.with_context(|| format!("a malformed row in {link}"))?;
        rows += 1;
        if rows > max_rows {
            continue;
        }
        let cells: Vec<String> = record.iter().map(format_cell).collect();
        md.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    if rows > max_rows {
        md.push_str(&format!(
            "\n{} more rows in [`{}`]({link}).\n",
            rows - max_rows,
            link.rsplit('/').next().unwrap_or(link)
        ));
    }
    Ok(md)
}

/// A CSV cell for the report: a number with a fraction to four significant
/// digits (`11.2298975` → `11.23`, `0.000123456` → `0.0001235`, `2.5e7` →
/// `2.500e7`), integers and text as written; `|` escaped.
pub fn format_cell(cell: &str) -> String {
    let trimmed = cell.trim();
    let is_integer = !trimmed.is_empty()
        && trimmed
            .strip_prefix('-')
            .unwrap_or(trimmed)
            .chars()
            .all(|c| c.is_ascii_digit());
    if is_integer {
        return trimmed.to_owned();
    }
    match trimmed.parse::<f64>() {
        Ok(x) if x.is_finite() && x != 0.0 => {
            let magnitude = x.abs().log10().floor() as i32;
            if (-4..6).contains(&magnitude) {
                let decimals = (3 - magnitude).max(0) as usize;
                format!("{x:.decimals$}")
            } else {
                format!("{x:.3e}")
            }
        }
        Ok(0.0) => "0".to_owned(),
        _ => trimmed.replace('|', "\\|"),
    }
}

/// The link from a file in folder `from_dir` to `target`, with `/`
/// separators: `relative_link("docs", "docs/results/cost.svg")` is
/// `results/cost.svg`, `relative_link("out", "docs/x.svg")` is
/// `../docs/x.svg`. Relative paths are taken from the current folder.
pub fn relative_link(from_dir: &Path, target: &Path) -> anyhow::Result<String> {
    let here = std::env::current_dir().context("cannot read the current folder")?;
    let from = normalise(&here.join(from_dir));
    let to = normalise(&here.join(target));
    let from_parts: Vec<Component> = from.components().collect();
    let to_parts: Vec<Component> = to.components().collect();
    let common = from_parts
        .iter()
        .zip(&to_parts)
        .take_while(|(a, b)| a == b)
        .count();
    let mut parts: Vec<String> = vec!["..".to_owned(); from_parts.len() - common];
    parts.extend(
        to_parts[common..]
            .iter()
            .map(|c| c.as_os_str().to_string_lossy().into_owned()),
    );
    Ok(parts.join("/"))
}

/// `path` with `.` dropped and `..` applied, without touching the disk.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// The calendar date (year, month, day) of a day counted from 1970-01-01,
/// by Howard Hinnant's `civil_from_days`: day 0 is 1970-01-01, day 11,017
/// is 2000-03-01.
pub fn civil_date(days_since_1970: i64) -> (i64, u32, u32) {
    let z = days_since_1970 + 719_468;
    let era = z.div_euclid(146_097);
    let day_of_era = z.rem_euclid(146_097);
    let year_of_era =
        (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_index = (5 * day_of_year + 2) / 153;
    let day = (day_of_year - (153 * month_index + 2) / 5 + 1) as u32;
    let month = if month_index < 10 {
        month_index + 3
    } else {
        month_index - 9
    } as u32;
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

/// Today's date (UTC) as `YYYY-MM-DD`.
pub fn today() -> String {
    let seconds = SystemTime::now()
        .duration_since(SystemTime::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let (y, m, d) = civil_date((seconds / 86_400) as i64);
    format!("{y:04}-{m:02}-{d:02}")
}

/// The machine in words: the CPU's model name (from `/proc/cpuinfo` where
/// there is one), the threads the studies may use, the architecture and
/// the instruction sets this binary was built for.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|name| name.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".to_owned());
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut features = Vec::new();
    if cfg!(target_feature = "avx512f") {
        features.push("AVX-512");
    } else if cfg!(target_feature = "avx2") {
        features.push("AVX2");
    }
    if cfg!(target_feature = "fma") {
        features.push("FMA");
    }
    let built = if features.is_empty() {
        String::new()
    } else {
        format!(" ({})", features.join(", "))
    };
    format!(
        "{cpu}, {threads} threads, {}{built}",
        std::env::consts::ARCH
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_the_calendars() {
        assert_eq!(civil_date(0), (1970, 1, 1));
        assert_eq!(civil_date(11_017), (2000, 3, 1));
        assert_eq!(civil_date(11_016), (2000, 2, 29));
        assert_eq!(civil_date(20_785), (2026, 11, 28));
        assert_eq!(civil_date(-1), (1969, 12, 31));
    }

    #[test]
    fn cells_keep_four_significant_digits() {
        assert_eq!(format_cell("11.2298975"), "11.23");
        assert_eq!(format_cell("13.418602499999999"), "13.42");
        assert_eq!(format_cell("0.000123456"), "0.0001235");
        assert_eq!(format_cell("25000000.0"), "2.500e7");
        assert_eq!(format_cell("1410"), "1410");
        assert_eq!(format_cell("-3"), "-3");
        assert_eq!(format_cell("0.0"), "0");
        assert_eq!(format_cell("NaN"), "NaN");
        assert_eq!(format_cell("exact"), "exact");
        assert_eq!(format_cell("a|b"), "a\\|b");
    }

    #[test]
    fn a_csv_becomes_a_table_cut_at_the_row_limit() {
        let csv = "method,elements,median_us\n\
                   dense,5,5.39123\n\
                   block,5,4.5801\n\
                   exact,5,5.0649\n";
        let expected = "| method | elements | median_us |\n\
                        | --- | --- | --- |\n\
                        | dense | 5 | 5.391 |\n\
                        | block | 5 | 4.580 |\n\
                        \n\
                        1 more rows in [`cost.csv`](results/cost.csv).\n";
        assert_eq!(
            csv_to_markdown(csv, "results/cost.csv", 2).unwrap(),
            expected
        );
    }

    #[test]
    fn the_report_has_one_header_line_then_a_section_per_study() {
        let header = ReportHeader {
            machine: "Test CPU, 2 threads, x86_64".to_owned(),
            date: "2026-11-28".to_owned(),
            quick: true,
            command: "helixhair bench --quick".to_owned(),
        };
        let sections = [Section {
            title: "cost: a title".to_owned(),
            charts: vec!["results/cost.svg".to_owned()],
            tables: vec![(
                "results/cost.csv".to_owned(),
                "method,median_us\nexact,9.58\n".to_owned(),
            )],
        }];
        let expected = "# Benchmarks\n\
            \n\
            Test CPU, 2 threads, x86_64 · 2026-11-28 · quick run (small sizes: checks that \
            every study runs, not the published figures)\n\
            \n\
            Rebuilt by `helixhair bench --quick`, which replaces this page and the files it \
            links; every figure below comes from that one run.\n\
            \n\
            ## cost: a title\n\
            \n\
            ![cost.svg](results/cost.svg)\n\
            \n\
            [`cost.csv`](results/cost.csv):\n\
            \n\
            | method | median_us |\n\
            | --- | --- |\n\
            | exact | 9.580 |\n\
            \n";
        assert_eq!(render_report(&header, &sections).unwrap(), expected);
    }

    #[test]
    fn links_are_relative_to_the_reports_folder() {
        assert_eq!(
            relative_link(Path::new("docs"), Path::new("docs/results/cost.svg")).unwrap(),
            "results/cost.svg"
        );
        assert_eq!(
            relative_link(Path::new("out/bench"), Path::new("out/bench/cost.svg")).unwrap(),
            "cost.svg"
        );
        assert_eq!(
            relative_link(Path::new("out"), Path::new("./docs/x.svg")).unwrap(),
            "../docs/x.svg"
        );
        assert_eq!(
            relative_link(Path::new(""), Path::new("a/b.csv")).unwrap(),
            "a/b.csv"
        );
    }

    #[test]
    fn only_files_written_during_the_run_are_reported() {
        let dir = std::env::temp_dir().join(format!("helixhair-report-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("cost.csv"), "method,median_us\nexact,9.58\n").unwrap();
        let header = ReportHeader {
            machine: "m".to_owned(),
            date: "d".to_owned(),
            quick: false,
            command: "c".to_owned(),
        };
        let report = dir.join("report.md");
        // The study ran but this run wrote nothing: cost.csv is an earlier
        // run's, so no section.
        write_report(&report, &[(Study::Cost, Vec::new())], &header).unwrap();
        let text = std::fs::read_to_string(&report).unwrap();
        assert!(!text.contains("## cost"), "{text}");
        // The run wrote it: its section and its table.
        write_report(
            &report,
            &[(Study::Cost, vec![dir.join("cost.csv")])],
            &header,
        )
        .unwrap();
        let text = std::fs::read_to_string(&report).unwrap();
        assert!(
            text.contains("## cost") && text.contains("| exact | 9.580 |"),
            "{text}"
        );
        assert!(text.contains("[`cost.csv`](cost.csv)"), "{text}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
