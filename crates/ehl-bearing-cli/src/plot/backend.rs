//! Output: SVG and supersampled PNG backends, the embedded font.

use super::*;

pub(crate) fn ensure_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok()
    });
    ensure!(ok, "the embedded plot font could not be loaded");
    Ok(())
}

pub(crate) fn drawing<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("plot drawing failed: {e}")
}

pub(crate) fn with_ext(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// A figure drawn identically on any backend.
pub(crate) trait Figure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Draws the figure with both backends and writes `<stem>.svg` and `<stem>.png`.
pub(crate) fn save_both<F: Figure>(stem: &Path, size: (u32, u32), fig: &F) -> Result<()> {
    ensure_font()?;
    if let Some(dir) = stem.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating plot directory {}", dir.display()))?;
    }

    let svg_path = with_ext(stem, "svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        fig.draw(&root)?;
        root.present().map_err(drawing)?;
    }
    // plotters writes a non-standard data URL for embedded images; make it one
    // that browsers and editors accept, and let the image stretch to its box.
    let svg = svg.replace(
        "href=\"data:png;base64,",
        "preserveAspectRatio=\"none\" href=\"data:image/png;base64,",
    );
    // Both files are written atomically (a temporary file, synced, renamed): a full disk never
    // leaves a truncated figure under its final name.
    ehl_bearing::io::write_atomic(&svg_path, svg.as_bytes())?;

    // PNG: drawn at SUPERSAMPLE times the size, then averaged down, which
    // anti-aliases lines and markers.
    let png_path = with_ext(stem, "png");
    let (bw, bh) = (size.0 * SUPERSAMPLE, size.1 * SUPERSAMPLE);
    let mut big = vec![255u8; bw as usize * bh as usize * 3];
    {
        let root = Png {
            inner: BitMapBackend::with_buffer(&mut big, (bw, bh)),
            size,
        }
        .into_drawing_area();
        fig.draw(&root)?;
        root.present().map_err(drawing)?;
    }
    let small = downsample(&big, size);
    // The encoder picks the format from the extension, so the temporary file ends in .png.
    let name = png_path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let tmp = png_path.with_file_name(format!(".{name}.tmp-{}.png", std::process::id()));
    let written = (|| {
        let mut out = BitMapBackend::new(&tmp, size);
        out.blit_bitmap((0, 0), size, &small).map_err(drawing)?;
        out.present()
            .map_err(|e| anyhow!("writing {}: {e}", tmp.display()))?;
        drop(out);
        std::fs::File::open(&tmp)
            .and_then(|f| f.sync_all())
            .with_context(|| format!("syncing {}", tmp.display()))?;
        std::fs::rename(&tmp, &png_path)
            .with_context(|| format!("renaming into {}", png_path.display()))
    })();
    if written.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    written
}

/// Linear scale of the PNG drawing buffer over the figure size.
pub(crate) const SUPERSAMPLE: u32 = 2;

/// Averages SUPERSAMPLE × SUPERSAMPLE blocks of an RGB buffer.
pub(crate) fn downsample(big: &[u8], (w, h): (u32, u32)) -> Vec<u8> {
    let k = SUPERSAMPLE as usize;
    let (w, h) = (w as usize, h as usize);
    let bw = w * k;
    let mut out = vec![0u8; w * h * 3];
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let mut sum = 0u32;
                for dy in 0..k {
                    for dx in 0..k {
                        sum += u32::from(big[((y * k + dy) * bw + x * k + dx) * 3 + c]);
                    }
                }
                out[(y * w + x) * 3 + c] = ((sum + (k * k / 2) as u32) / (k * k) as u32) as u8;
            }
        }
    }
    out
}

/// A stroke style scaled for the supersampled buffer.
pub(crate) struct Scaled {
    pub(crate) color: BackendColor,
    pub(crate) width: u32,
}

impl plotters_backend::BackendStyle for Scaled {
    fn color(&self) -> BackendColor {
        self.color
    }
    fn stroke_width(&self) -> u32 {
        self.width
    }
}

pub(crate) fn scaled<S: plotters_backend::BackendStyle>(style: &S) -> Scaled {
    Scaled {
        color: style.color(),
        width: style.stroke_width() * SUPERSAMPLE,
    }
}

pub(crate) fn up((x, y): BackendCoord) -> BackendCoord {
    let k = SUPERSAMPLE as i32;
    (x * k, y * k)
}

/// The PNG backend: plotters' bitmap backend drawn at [`SUPERSAMPLE`] times the
/// figure size (plotters sees the figure size), with its own text rendering:
/// plotters' `ab_glyph` text drops each glyph's side bearing, which makes
/// labels look unevenly spaced ("0. 8").
pub(crate) struct Png<'a> {
    pub(crate) inner: BitMapBackend<'a>,
    pub(crate) size: (u32, u32),
}

pub(crate) fn font_ref() -> &'static ab_glyph::FontRef<'static> {
    static FONT_REF: OnceLock<ab_glyph::FontRef<'static>> = OnceLock::new();
    FONT_REF.get_or_init(|| {
        // ensure_font() has already parsed the same bytes successfully.
        ab_glyph::FontRef::try_from_slice(FONT_BYTES).expect("embedded font parses")
    })
}

/// Width, height and ascent in pixels of `text` at plotters' font `size`.
pub(crate) fn text_box(text: &str, size: f64) -> (f32, f32, f32) {
    use ab_glyph::{Font, ScaleFont};
    let font = font_ref().as_scaled(size as f32);
    let mut width = 0.0f32;
    let mut prev = None;
    for c in text.chars() {
        let id = font.glyph_id(c);
        if let Some(p) = prev {
            width += font.kern(p, id);
        }
        width += font.h_advance(id);
        prev = Some(id);
    }
    (width, font.ascent() - font.descent(), font.ascent())
}

impl<'a> DrawingBackend for Png<'a> {
    type ErrorType = <BitMapBackend<'a> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.size
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }
    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let k = SUPERSAMPLE as i32 - 1;
        let (x, y) = up(point);
        let fill = Scaled { color, width: 1 };
        self.inner.draw_rect((x, y), (x + k, y + k), &fill, true)
    }
    fn draw_line<S: plotters_backend::BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(up(from), up(to), &scaled(style))
    }
    fn draw_rect<S: plotters_backend::BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let k = if fill { SUPERSAMPLE as i32 - 1 } else { 0 };
        let (x1, y1) = up(bottom_right);
        self.inner
            .draw_rect(up(upper_left), (x1 + k, y1 + k), &scaled(style), fill)
    }
    fn draw_path<S: plotters_backend::BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner
            .draw_path(path.into_iter().map(up), &scaled(style))
    }
    fn draw_circle<S: plotters_backend::BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner
            .draw_circle(up(center), radius * SUPERSAMPLE, &scaled(style), fill)
    }
    fn fill_polygon<S: plotters_backend::BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner
            .fill_polygon(vert.into_iter().map(up), &scaled(style))
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (w, h): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let k = SUPERSAMPLE as usize;
        let (w, h) = (w as usize, h as usize);
        let mut big = Vec::with_capacity(w * h * k * k * 3);
        for row in src.chunks_exact(w * 3).take(h) {
            let start = big.len();
            for px in row.chunks_exact(3) {
                for _ in 0..k {
                    big.extend_from_slice(px);
                }
            }
            for _ in 1..k {
                big.extend_from_within(start..start + w * k * 3);
            }
        }
        let size = ((w * k) as u32, (h * k) as u32);
        self.inner.blit_bitmap(up(pos), size, &big)
    }

    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let (w, h, _) = text_box(text, style.size());
        Ok((w.ceil() as u32, h.ceil() as u32))
    }

    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        use ab_glyph::{Font, ScaleFont};
        let colour = style.color();
        if colour.alpha == 0.0 || text.is_empty() {
            return Ok(());
        }
        let k = SUPERSAMPLE as f64;
        let size = (style.size() * k) as f32;
        let (w, h, ascent) = text_box(text, style.size() * k);
        let pos = up(pos);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Center => -w / 2.0,
            HPos::Right => -w,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0.0,
            VPos::Center => -h / 2.0,
            VPos::Bottom => -h,
        };
        let transform = style.transform();
        let font = font_ref().as_scaled(size);
        let mut caret = dx;
        let mut prev = None;
        let mut result = Ok(());
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = prev {
                caret += font.kern(p, id);
            }
            let glyph = id.with_scale_and_position(size, ab_glyph::point(caret, dy + ascent));
            if let Some(outline) = font_ref().outline_glyph(glyph) {
                let b = outline.px_bounds();
                outline.draw(|gx, gy, coverage| {
                    if result.is_err() || coverage <= 0.0 {
                        return;
                    }
                    let lx = b.min.x as i32 + gx as i32;
                    let ly = b.min.y as i32 + gy as i32;
                    let (tx, ty) = transform.transform(lx, ly);
                    let c = BackendColor {
                        alpha: colour.alpha * f64::from(coverage.min(1.0)),
                        rgb: colour.rgb,
                    };
                    result = self.inner.draw_pixel((pos.0 + tx, pos.1 + ty), c);
                });
            }
            caret += font.h_advance(id);
            prev = Some(id);
        }
        result
    }
}

/// Lines of `title` wrapped at word boundaries to `width` pixels at font size `size` (an
/// explicit "\n" also breaks).
pub(crate) fn wrap_title(title: &str, size: f64, width: f32) -> Vec<String> {
    // "a = 1 mm" and "x ± e" stay on one line.
    let title = title
        .replace(" = ", "\u{a0}=\u{a0}")
        .replace(" ± ", "\u{a0}±\u{a0}");
    let mut lines = Vec::new();
    for para in title.split('\n') {
        let mut cur = String::new();
        for word in para.split(' ') {
            let trial = if cur.is_empty() {
                word.to_string()
            } else {
                format!("{cur} {word}")
            };
            if !cur.is_empty() && text_box(&trial, size).0 > width {
                lines.push(std::mem::replace(&mut cur, word.to_string()));
            } else {
                cur = trial;
            }
        }
        lines.push(cur);
    }
    lines
}

/// Draws `title` centred at the top of `root`, wrapped to the figure width (the font shrinks
/// from the title size to 80 % of it if that saves a line), and returns the area below it.
pub(crate) fn title_area<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<DrawingArea<DB, Shift>> {
    let (w, _) = root.dim_in_pixel();
    let width = w.saturating_sub(2 * MARGIN) as f32;
    let mut size = TITLE_SIZE as f64;
    let mut lines = wrap_title(title, size, width);
    let small = 0.8 * TITLE_SIZE as f64;
    let fewer = wrap_title(title, small, width);
    if fewer.len() < lines.len() {
        size = small;
        lines = fewer;
    }
    let line_h = (size * 1.25).ceil() as u32;
    let top = 8 + line_h * lines.len() as u32 + 6;
    let (head, rest) = root.split_vertically(top);
    let style = TextStyle::from((FONT, size).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    for (k, line) in lines.iter().enumerate() {
        head.draw_text(
            line,
            &style,
            ((w / 2) as i32, (8 + line_h * k as u32) as i32),
        )
        .map_err(drawing)?;
    }
    Ok(rest)
}
