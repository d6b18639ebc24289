#include "wavebench/daemon/accounts.hpp"

#include <sodium.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>
#include <sstream>

namespace wavebench::daemon {

namespace {

void ensure_sodium() {
  // sodium_init is thread-safe and idempotent; it fails only when no randomness is available.
  if (sodium_init() < 0) throw std::runtime_error("libsodium: cannot initialise");
}

std::string shown(const std::string& value) {
  std::string out;
  for (const unsigned char c : value.substr(0, 80)) out += (c >= 0x20 && c < 0x7f) ? char(c) : '?';
  return value.size() > 80 ? out + "..." : out;
}

}  // namespace

const char* role_name(Role role) {
  return role == Role::kEngineer ? "engineer" : "operator";
}

bool valid_account_name(std::string_view name) {
  return !name.empty() && name.size() <= kMaxAccountNameLength &&
         name.find_first_not_of(
             "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") ==
             std::string_view::npos;
}

const Account* Accounts::find(std::string_view name) const {
  for (const auto& a : accounts_) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

Accounts parse_accounts(const std::string& yaml_text, const std::string& source) {
  const auto refuse = [&](const std::string& key, const std::string& value,
                          const std::string& expected) {
    throw AccountsFileRefused("accounts file " + source + ": " + key + ": got '" + shown(value) +
                              "', expected " + expected);
  };
  if (yaml_text.size() > kMaxAccountsFileBytes) {
    refuse("(file)", std::to_string(yaml_text.size()) + " bytes",
           "at most " + std::to_string(kMaxAccountsFileBytes) + " bytes");
  }
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    refuse("(file)", e.what(), "YAML");
  }
  if (!root.IsMap()) refuse("(file)", yaml_text.substr(0, 40), "a map with the key 'accounts'");
  for (const auto& entry : root) {
    const auto key = entry.first.as<std::string>("");
    if (key != "accounts") refuse(key, "(a key)", "only 'accounts'");
  }
  const auto list = root["accounts"];
  if (!list || !list.IsSequence()) {
    refuse("accounts", list ? YAML::Dump(list) : "nothing",
           "a list of {name, password_hash, role}");
  }
  if (list.size() > kMaxAccounts) {
    refuse("accounts", std::to_string(list.size()) + " entries",
           "at most " + std::to_string(kMaxAccounts));
  }
  std::vector<Account> accounts;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto item = list[i];
    const std::string at = "accounts[" + std::to_string(i) + "]";
    if (!item.IsMap()) refuse(at, YAML::Dump(item), "a map {name, password_hash, role}");
    for (const auto& field : item) {
      const auto key = field.first.as<std::string>("");
      if (key != "name" && key != "password_hash" && key != "role") {
        refuse(at + "." + key, "(a key)", "name, password_hash or role");
      }
    }
    const auto text = [&](const char* key) {
      const auto node = item[key];
      if (!node || !node.IsScalar()) {
        refuse(at + "." + key, node ? YAML::Dump(node) : "nothing", "a string");
      }
      return node.as<std::string>();
    };
    Account a;
    a.name = text("name");
    if (!valid_account_name(a.name)) {
      refuse(at + ".name", a.name,
             "1 to " + std::to_string(kMaxAccountNameLength) + " of A-Z a-z 0-9 . _ -");
    }
    if (!names.insert(a.name).second) refuse(at + ".name", a.name, "a name not used before");
    a.password_hash = text("password_hash");
    if (a.password_hash.size() >= crypto_pwhash_STRBYTES ||
        a.password_hash.rfind("$argon2id$", 0) != 0) {
      refuse(at + ".password_hash", a.password_hash,
             "an Argon2id hash from `wavebench account hash` ($argon2id$...)");
    }
    const auto role = text("role");
    if (role == "operator") {
      a.role = Role::kOperator;
    } else if (role == "engineer") {
      a.role = Role::kEngineer;
    } else {
      refuse(at + ".role", role, "operator or engineer");
    }
    accounts.push_back(std::move(a));
  }
  return Accounts(std::move(accounts));
}

Accounts load_accounts(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::is_regular_file(status)) {
    throw AccountsFileRefused("accounts file " + path.string() + ": --accounts: got '" +
                              path.string() + "', expected a readable regular file");
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxAccountsFileBytes) {
    throw AccountsFileRefused("accounts file " + path.string() + ": (file): got " +
                              std::to_string(size) + " bytes, expected at most " +
                              std::to_string(kMaxAccountsFileBytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw AccountsFileRefused("accounts file " + path.string() +
                              ": cannot read; expected a readable regular file");
  }
  std::string text(kMaxAccountsFileBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return parse_accounts(text, path.string());
}

std::string accounts_yaml(const Accounts& accounts) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "accounts" << YAML::Value << YAML::BeginSeq;
  for (const auto& a : accounts.all()) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << a.name << YAML::Key
        << "password_hash" << YAML::Value << YAML::DoubleQuoted << a.password_hash << YAML::Key
        << "role" << YAML::Value << role_name(a.role) << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string hash_password(std::string_view password) {
  if (password.empty() || password.size() > kMaxPasswordLength) {
    throw std::invalid_argument("password: got " + std::to_string(password.size()) +
                                " characters, expected 1 to " + std::to_string(kMaxPasswordLength));
  }
  ensure_sodium();
  char out[crypto_pwhash_STRBYTES];
  if (crypto_pwhash_str_alg(out, password.data(), password.size(),
                            crypto_pwhash_OPSLIMIT_INTERACTIVE, crypto_pwhash_MEMLIMIT_INTERACTIVE,
                            crypto_pwhash_ALG_ARGON2ID13) != 0) {
    throw std::runtime_error("libsodium: hashing the password failed (out of memory?)");
  }
  return out;
}

bool verify_password(std::string_view hash, std::string_view password) {
  if (password.size() > kMaxPasswordLength || hash.size() >= crypto_pwhash_STRBYTES) return false;
  ensure_sodium();
  char stored[crypto_pwhash_STRBYTES] = {};
  hash.copy(stored, hash.size());
  return crypto_pwhash_str_verify(stored, password.data(), password.size()) == 0;
}

void verify_nothing(std::string_view password) {
  static const std::string dummy = hash_password("wavebench: no such account");
  (void)verify_password(dummy, password);
}

}  // namespace wavebench::daemon
