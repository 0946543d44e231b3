//! A solver's history as files: `<solver>.csv` (SI, one row per step, empty cells for what the
//! solver does not produce) and `<solver>.json` (the same rows plus metadata). Numbers are
//! written in their shortest round-trip form ([`cell`]): a value read back from the CSV is the
//! computed one, bit for bit, so a stored copy or a baseline compares at round-off.

use std::path::Path;

use super::figures::surface::FieldView;
use spherecontact_model::history::{History, Quantity};
use spherecontact_model::number::cell;
use spherecontact_system::io::write_atomically;

/// The CSV header: the path columns, then every quantity.
pub fn csv_header() -> Vec<&'static str> {
    spherecontact_external::exchange::results_csv::columns()
}

/// The CSV text of a history.
pub fn to_csv(history: &History) -> anyhow::Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(csv_header())?;
    for row in &history.steps {
        let mut record = vec![
            row.step.to_string(),
            row.position.map_or_else(String::new, |p| p.to_string()),
            cell(Some(row.delta_n)),
            cell(Some(row.delta_t)),
        ];
        record.extend(Quantity::ALL.iter().map(|q| cell(q.of(row))));
        writer.write_record(&record)?;
    }
    Ok(String::from_utf8(writer.into_inner()?)?)
}

/// The CSV text of a history's surface fields: one row per sample point, empty cells for what
/// the solver does not resolve (`stick` is 1, 0, or empty outside the contact; `slip_x`,
/// `slip_y` the relative tangential displacement of the surfaces; `traction_y`, `slip_y` empty
/// for a model that takes the traction along x).
pub fn fields_to_csv(history: &History) -> anyhow::Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record([
        "position",
        "x",
        "y",
        "pressure",
        "traction_x",
        "traction_y",
        "stick",
        "slip_x",
        "slip_y",
    ])?;
    for field in FieldView::all(history) {
        for i in 0..field.len() {
            let [x, y] = field.point(i);
            let stick = field
                .stick(i)
                .filter(|_| field.in_contact(i))
                .map(|s| u8::from(s).to_string());
            writer.write_record([
                field.position().to_string(),
                cell(Some(x)),
                cell(Some(y)),
                cell(Some(field.pressure(i))),
                cell(field.traction(i).map(|t| t[0])),
                cell(field.traction_y(i)),
                stick.unwrap_or_default(),
                cell(field.slip(i).map(|s| s[0])),
                cell(field.slip_y(i)),
            ])?;
        }
    }
    Ok(String::from_utf8(writer.into_inner()?)?)
}

/// Writes `<dir>/<solver>.csv` and `<dir>/<solver>.json`, and `<dir>/<solver>.fields.csv` when
/// the solver resolves surface fields; each atomically.
pub fn write(dir: &Path, history: &History) -> anyhow::Result<()> {
    let name = &history.metadata.solver;
    write_atomically(&dir.join(format!("{name}.csv")), to_csv(history)?.as_bytes())?;
    if !history.fields.is_empty() {
        write_atomically(
            &dir.join(format!("{name}.fields.csv")),
            fields_to_csv(history)?.as_bytes(),
        )?;
    }
    let json = serde_json::to_string_pretty(history)?;
    write_atomically(&dir.join(format!("{name}.json")), json.as_bytes())?;
    Ok(())
}

/// Writes every history of a case run into `dir` (created if missing), as [`write`] does.
pub fn write_all(dir: &Path, run: &spherecontact_verify::CaseRun) -> anyhow::Result<()> {
    spherecontact_system::io::create_folder(dir)?;
    for history in run.histories.values().flatten() {
        write(dir, history)?;
    }
    Ok(())
}
