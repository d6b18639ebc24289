#pragma once
// Operators by name (issue #21): the accounts file the daemon reads (--accounts FILE), YAML
//
//   accounts:
//     - name: anna
//       password_hash: "$argon2id$v=19$m=65536,t=2,p=1$..."   # wavebench account hash
//       role: operator            # or engineer
//
// Hashes are libsodium's crypto_pwhash_str (Argon2id, its "interactive" cost): memory-hard,
// salted, the parameters inside the string. Roles: an operator starts and stops runs with the
// shipped specs (and jogs); an engineer also changes specs and bench settings (a run with a
// spec or limits not from the specs folder, the bench check, reset). The daemon's bearer token
// acts as an engineer (automation).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace wavebench::daemon {

enum class Role { kOperator, kEngineer };
const char* role_name(Role role);

struct Account {
  std::string name;
  std::string password_hash;
  Role role = Role::kOperator;
};

inline constexpr std::size_t kMaxAccountsFileBytes = 256 * 1024;
inline constexpr std::size_t kMaxAccounts = 1000;
inline constexpr std::size_t kMaxAccountNameLength = 64;
inline constexpr std::size_t kMaxPasswordLength = 1024;

// An accounts file the daemon will not use: a configuration error (exit 2); what() names the
// file, the key, the value and what was expected.
class AccountsFileRefused : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class Accounts {
 public:
  Accounts() = default;
  explicit Accounts(std::vector<Account> accounts) : accounts_(std::move(accounts)) {}
  const Account* find(std::string_view name) const;
  std::size_t size() const { return accounts_.size(); }
  bool empty() const { return accounts_.empty(); }
  const std::vector<Account>& all() const { return accounts_; }

 private:
  std::vector<Account> accounts_;
};

// Reads and checks the whole file (bounded: kMaxAccountsFileBytes, kMaxAccounts, names of 1 to
// kMaxAccountNameLength of A-Z a-z 0-9 . _ -, each once, an Argon2id hash, a known role).
Accounts load_accounts(const std::filesystem::path& path);
Accounts parse_accounts(const std::string& yaml_text, const std::string& source);

// The Argon2id string of `password` (libsodium, interactive cost). Throws std::invalid_argument
// for an empty or over-long password, std::runtime_error when libsodium fails (out of memory).
std::string hash_password(std::string_view password);
// Whether `password` matches `hash` (constant time in libsodium). A password longer than
// kMaxPasswordLength never matches.
bool verify_password(std::string_view hash, std::string_view password);
// Costs what a real verification costs: a login for an unknown name takes as long as a wrong
// password for a known one, so names cannot be probed by timing.
void verify_nothing(std::string_view password);

// The accounts as the file's YAML (what `wavebench account add` writes).
std::string accounts_yaml(const Accounts& accounts);

// Whether `name` is a valid account name (the same rule the file is checked against).
bool valid_account_name(std::string_view name);

}  // namespace wavebench::daemon
