// The pixels of the page's canvases, for the browser drivers: per canvas
// the colours seen (every seventh pixel) and a hash of every pixel.

/** Colours (sampled) and a hash of each canvas matching `selector`. */
export const canvases = (page, selector) => page.evaluate((sel) => [...document.querySelectorAll(sel)].map((c) => {
  const d = document.createElement('canvas');
  d.width = c.width;
  d.height = c.height;
  const x = d.getContext('2d');
  x.drawImage(c, 0, 0);
  const data = x.getImageData(0, 0, d.width, d.height).data;
  const colours = new Set();
  let hash = 0;
  for (let i = 0; i < data.length; i += 4) {
    const v = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
    if (i % 28 === 0) colours.add(v);
    hash = (Math.imul(hash, 31) + v) >>> 0;
  }
  return { width: c.width, height: c.height, colours: colours.size, hash };
}), selector);
